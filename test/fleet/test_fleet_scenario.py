"""fleet on a simulated fleet of 20 vehicles flying 30 flights each, with real vehicles' part spread
(scripts/simulate_fleet.py): one propeller wears flight by flight, one vehicle gets a propeller of
another make halfway, one pack ages. Judged twice, as an operator's fleet grows: after 16 flights
(the worn propeller still inside the healthy band) and after all 30. The report names the worn
rotor before it leaves the band, the swap as a step and not wear, the ageing pack, and nothing
on the other vehicles."""
import os
import shutil
import subprocess
import tempfile

import pytest
import simulate_fleet
from conftest import fleet_command, simulate_fleet as simulate, variant

from fleet_lib import analysis, database, description

SCENARIO = simulate_fleet.SCENARIO
WORN = simulate_fleet.vehicle_name(SCENARIO["worn"]["vehicle"])
SWAPPED = simulate_fleet.vehicle_name(SCENARIO["swap"]["vehicle"])
AGEING = simulate_fleet.vehicle_name(SCENARIO["ageing_pack"]["vehicle"])
STAGE_ONE = 16  # flights into the fleet's life when it is first judged


@pytest.fixture(scope="module")
def fleet():
    folder = tempfile.mkdtemp(prefix="fleet-scenario-")
    try:
        simulate(folder, 20, 30, 2027)
        yield folder
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def findings(path):
    fleet = description.load(path)
    connection = database.connect(fleet.database)
    try:
        vehicles, found = analysis.analyse(fleet, database.flights(connection))
    finally:
        connection.close()
    with open(os.path.join(fleet.report, "README.md")) as handle:
        report = handle.read()
    return vehicles, found, report


def test_the_report_names_the_worn_rotor_early_the_swap_as_a_step_and_the_ageing_pack_and_nothing_else(fleet):
    assert simulate_fleet.worn_factor(STAGE_ONE) > 0.95  # inside the band at the first judgement
    stage = os.path.join(fleet, "stage_one")
    os.mkdir(stage)
    for log in os.listdir(os.path.join(fleet, "logs")):
        if int(log.split("_flight_")[1][:3]) <= STAGE_ONE:
            os.symlink(os.path.join(fleet, "logs", log), os.path.join(stage, log))
    early = variant(fleet, "stage_one", logs=["stage_one/*.ulg"])
    subprocess.run(fleet_command(early, "--jobs", "2", "--quiet"), check=True)
    vehicles, found, report = findings(early)
    assert len(vehicles) == 20 and all(len(v["flights"]) == STAGE_ONE for v in vehicles.values())
    wear = [f for f in found if f.kind == "wear"]
    assert [(f.vehicle, f.subject) for f in wear] == [(WORN, "motor %d" % SCENARIO["worn"]["motor"])], report
    story = vehicles[WORN]["rotors"][SCENARIO["worn"]["motor"]]["story"]
    assert not story["outside"] and story["leaves_in"] > 0
    assert "leaves the healthy band" in wear[0].line and wear[0].line in report
    assert {f.vehicle for f in found if f.attention} <= {WORN, AGEING}, report

    # The rest of the fleet's flights: the same database, only the new logs are run.
    whole = os.path.join(fleet, "fleet.yaml")
    done = subprocess.run(fleet_command(whole, "--jobs", "2", "--quiet"), check=True, stdout=subprocess.PIPE, text=True)
    assert "fleet: %d new flights (0 refused)" % (20 * (30 - STAGE_ONE)) in done.stdout
    vehicles, found, report = findings(whole)
    assert all(len(v["flights"]) == 30 for v in vehicles.values())
    named = sorted((f.vehicle, f.subject, f.kind) for f in found)
    assert named == sorted([(AGEING, "pack %s%s" % (AGEING, SCENARIO["ageing_pack"]["pack"]), "pack_ageing"),
                            (WORN, "motor %d" % SCENARIO["worn"]["motor"], "wear"),
                            (SWAPPED, "motor %d" % SCENARIO["swap"]["motor"], "step")]), report
    step = vehicles[SWAPPED]["rotors"][SCENARIO["swap"]["motor"]]["story"]
    assert step["at"] + 1 == SCENARIO["swap"]["from_flight"]
    assert {f.vehicle for f in found if f.attention} == {WORN, AGEING}
    for finding in found:
        assert finding.line in report
    print(report.split("## Vehicles")[0])
