"""fleet's inputs: a description that cannot be used is refused in one line naming the file and
the key; a database of a newer schema is refused; migrations bring an older one up."""
import os
import sqlite3

import pytest

from fleet_lib import database, description


@pytest.fixture
def folder(tmp_path):
    for name in ("model.yaml", "vehicle.urdf", "reference.yaml"):
        (tmp_path / name).write_text("x: 1\n")
    return tmp_path


def refusal(folder, text):
    path = folder / "fleet.yaml"
    path.write_text(text)
    with pytest.raises(description.DescriptionError) as error:
        description.load(str(path))
    return str(error.value)


def test_a_good_description_loads_with_its_paths_from_its_folder(folder):
    path = folder / "fleet.yaml"
    path.write_text("vehicles:\n  - {name: v1, model: model.yaml, urdf: vehicle.urdf, reference: reference.yaml,"
                    " logs: 'logs/v1/*.ulg', pack: P7}\nhealthy_band: 0.04\n")
    fleet = description.load(str(path))
    assert fleet.vehicles["v1"].model == str(folder / "model.yaml")
    assert fleet.vehicles["v1"].logs == [str(folder / "logs/v1/*.ulg")]
    assert fleet.database == str(folder / "fleet.sqlite") and fleet.healthy_band == 0.04


@pytest.mark.parametrize("text, line", [
    ("vehicles: []\n", "fleet.yaml: vehicles: expected a list of vehicles, got []"),
    ("vehicles:\n  - {name: v1, model: missing.yaml, urdf: vehicle.urdf}\n", "vehicles[v1].model: "),
    ("vehicles:\n  - {name: v1, model: model.yaml}\n", "fleet.yaml: vehicles[0].urdf: missing"),
    ("vehicles:\n  - {name: v1, model: model.yaml, urdf: vehicle.urdf, colour: red}\n",
     "fleet.yaml: vehicles[0].colour: unknown key"),
    ("vehicles:\n  - {name: 'v 1', model: model.yaml, urdf: vehicle.urdf}\n",
     "fleet.yaml: vehicles[0].name: 'v 1' is not a name"),
    ("vehicles:\n  - {name: v1, model: model.yaml, urdf: vehicle.urdf}\n  - {name: v1, model: model.yaml, urdf: "
     "vehicle.urdf}\n", "fleet.yaml: vehicles[1].name: 'v1' is given twice"),
    ("vehicles:\n  - {name: v1, model: model.yaml, urdf: vehicle.urdf}\nlogs: 'in/*.ulg'\n",
     "fleet.yaml: vehicle_pattern: missing"),
    ("vehicles:\n  - {name: v1, model: model.yaml, urdf: vehicle.urdf}\nlogs: 'in/*.ulg'\nvehicle_pattern: '^(v[0-9]+)'\n",
     "fleet.yaml: vehicle_pattern: '^(v[0-9]+)' has no (?P<vehicle>...) group"),
    ("vehicles:\n  - {name: v1, model: model.yaml, urdf: vehicle.urdf}\nvehicle_pattern: '^(v[0-9]+)'\n",
     "fleet.yaml: vehicle_pattern: '^(v[0-9]+)' has no (?P<vehicle>...) group"),
    ("vehicles:\n  - {name: v1, model: model.yaml, urdf: vehicle.urdf}\nhealthy_band: 2\n",
     "fleet.yaml: healthy_band: 2 is outside 0.005..0.5"),
    ("vehicles:\n  - {name: v1, model: model.yaml, urdf: vehicle.urdf, empty_mass_kg: -1}\n",
     "fleet.yaml: vehicles[v1].empty_mass_kg: -1 is not a positive mass in kg"),
    ("vehicles: [\n", "fleet.yaml: not YAML"),
    ("vehicles:\n  - {name: v1, model: model.yaml, urdf: vehicle.urdf}\ndatabase: 5\n",
     "fleet.yaml: database: expected a path, got 5"),
])
def test_a_bad_description_is_refused_in_one_line_naming_the_key(folder, text, line):
    message = refusal(folder, text)
    assert line in message, message
    assert "\n" not in message


def test_logs_go_to_the_vehicle_the_pattern_names_and_an_unknown_vehicle_is_a_problem(folder):
    (folder / "in").mkdir()
    for name in ("v1_flight_2_pack-A.ulg", "v1_flight_10_pack-B.ulg", "v9_flight_1.ulg", "stray.ulg"):
        (folder / "in" / name).write_text("")
    (folder / "fleet.yaml").write_text(
        "vehicles:\n  - {name: v1, model: model.yaml, urdf: vehicle.urdf}\nlogs: 'in/*.ulg'\n"
        "vehicle_pattern: '^(?P<vehicle>v[0-9]+)_'\npack_pattern: 'pack-(?P<pack>[A-Z])'\n")
    found = [(v, os.path.basename(log), pack, problem)
             for v, log, pack, problem in description.logs(description.load(str(folder / "fleet.yaml")))]
    assert found == [
        ("", "stray.ulg", None, "its name does not match vehicle_pattern '^(?P<vehicle>v[0-9]+)_'"),
        ("v1", "v1_flight_2_pack-A.ulg", "A", None),
        ("v1", "v1_flight_10_pack-B.ulg", "B", None),
        ("v9", "v9_flight_1.ulg", None, "vehicle 'v9' is not in the fleet description"),
    ]


def test_a_database_of_a_newer_schema_is_refused_and_an_empty_one_is_migrated(tmp_path):
    path = str(tmp_path / "fleet.sqlite")
    connection = database.connect(path)
    assert connection.execute("PRAGMA user_version").fetchone()[0] == database.VERSION
    assert {"runs", "flights", "hovers", "rotors"} <= {
        row[0] for row in connection.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}
    connection.close()
    raw = sqlite3.connect(path)
    raw.execute("PRAGMA user_version = %d" % (database.VERSION + 1))
    raw.close()
    with pytest.raises(database.DatabaseError) as error:
        database.connect(path)
    assert "schema version %d is newer than this build's %d" % (database.VERSION + 1, database.VERSION) in str(error.value)
    (tmp_path / "text.sqlite").write_text("not a database at all, but long enough to be read as one" * 20)
    with pytest.raises(database.DatabaseError) as error:
        database.connect(str(tmp_path / "text.sqlite"))
    assert "not an SQLite database" in str(error.value)


def a_row(log, digest, status="estimated", factor=1.0):
    return dict(vehicle="v1", log=log, log_sha256=digest, log_time_utc=None, pack=None, status=status,
                problem=None if status == "estimated" else "a line", reference="vehicle", duration_s=60.0,
                hover_mass_kg=1.3, pack_resistance_ohm=None, pack_resistance_std_ohm=None, supply_resistance_ohm=None,
                esc_verdict="consistent", flagged_channel=0, warnings=[],
                hovers=[dict(start_s=1.0, end_s=20.0, total_mass_kg=1.3, payload_kg=0.0)],
                rotors=[dict(channel=k, factor=factor, factor_std=0.01, factor_low=factor - 0.02,
                             factor_high=factor + 0.02) for k in (1, 2, 3, 4)])


def test_a_flight_is_written_whole_or_not_at_all(tmp_path):
    connection = database.connect(str(tmp_path / "fleet.sqlite"))
    run = database.start_run(connection, "2026-12-03T00:00:00+00:00", "fleet.yaml", "jobs 1")
    broken = a_row("a.ulg", "aa")
    broken["rotors"][3]["factor"] = None  # fails on the last rotor, after the flight and its hovers
    with pytest.raises(sqlite3.IntegrityError):
        database.insert_flight(connection, broken, run)
    assert database.flights(connection) == []
    assert connection.execute("SELECT COUNT(*) FROM hovers").fetchone()[0] == 0
    assert database.insert_flight(connection, a_row("a.ulg", "aa"), run)
    assert not database.insert_flight(connection, a_row("copy_of_a.ulg", "aa"), run)  # same content: kept once
    assert [f["log"] for f in database.flights(connection)] == ["a.ulg"]


def test_a_refused_or_damaged_log_is_replaced_when_it_is_tried_again(tmp_path):
    connection = database.connect(str(tmp_path / "fleet.sqlite"))
    run = database.start_run(connection, "2026-12-03T00:00:00+00:00", "fleet.yaml", "jobs 1")
    database.insert_flight(connection, a_row("b.ulg", "b-partial", status="damaged"), run)  # read while copied
    database.insert_flight(connection, a_row("c.ulg", "cc", status="refused"), run)  # its vehicle not described yet
    assert database.seen(connection) == {("v1", "b-partial")}  # a refused log is tried again
    database.insert_flight(connection, a_row("b.ulg", "b-whole"), run)
    database.insert_flight(connection, a_row("c.ulg", "cc"), run)
    kept = {f["log"]: f for f in database.flights(connection)}
    assert {log: (f["log_sha256"], f["status"]) for log, f in kept.items()} == {
        "b.ulg": ("b-whole", "estimated"), "c.ulg": ("cc", "estimated")}
    assert connection.execute("SELECT COUNT(*) FROM rotors").fetchone()[0] == 8
