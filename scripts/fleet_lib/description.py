"""The fleet description (docs/fleet.md): its vehicles, each with its model, its healthy reference
and where its logs are. Paths are relative to the description's folder. Every refusal is one line
naming the file and the key: DescriptionError."""
import dataclasses
import glob
import os
import re

import yaml


class DescriptionError(Exception):
    """A fleet description that cannot be used, one line: "<file>: <key>: <problem>"."""


VEHICLE_KEYS = {"name", "model", "reference", "urdf", "empty_mass_kg", "params", "logs", "pack", "pack_pattern"}
FLEET_KEYS = {"vehicles", "logs", "vehicle_pattern", "pack_pattern", "database", "report", "healthy_band"}


@dataclasses.dataclass
class Vehicle:
    """One vehicle: its name, files (absolute paths) and log patterns."""
    name: str
    model: str
    urdf: str
    reference: str = None
    empty_mass_kg: float = None
    params: str = None
    logs: list = dataclasses.field(default_factory=list)
    pack: str = None
    pack_pattern: re.Pattern = None


@dataclasses.dataclass
class Fleet:
    """The description: vehicles by name, fleet-level log patterns with the pattern that names a
    log's vehicle, where the database and the report go, the healthy band of a rotor factor."""
    path: str
    vehicles: dict
    logs: list
    vehicle_pattern: re.Pattern
    pack_pattern: re.Pattern
    database: str
    report: str
    healthy_band: float


def _fail(path, key, problem):
    raise DescriptionError("%s: %s: %s" % (path, key, problem))


def _pattern(path, key, text, group=None):
    try:
        compiled = re.compile(text)
    except re.error as error:
        _fail(path, key, "'%s' is not a regular expression (%s)" % (text, error))
    if group and group not in compiled.groupindex:
        _fail(path, key, "'%s' has no (?P<%s>...) group" % (text, group))
    if not group and compiled.groups < 1 and "pack" not in compiled.groupindex:
        _fail(path, key, "'%s' captures nothing: put the pack's identity in a group" % text)
    return compiled


def _file(path, folder, key, value):
    if not isinstance(value, str) or not value:
        _fail(path, key, "expected a file name, got %r" % (value,))
    full = os.path.normpath(os.path.join(folder, value))
    if not os.path.isfile(full):
        _fail(path, key, "%s does not exist" % full)
    return full


def _patterns(path, folder, key, value):
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(v, str) and v for v in value):
        _fail(path, key, "expected a log pattern or a list of them, got %r" % (value,))
    return [os.path.normpath(os.path.join(folder, v)) for v in value]


def _vehicle(path, folder, index, entry):
    where = "vehicles[%d]" % index
    if not isinstance(entry, dict):
        _fail(path, where, "expected a mapping, got %r" % (entry,))
    unknown = sorted(set(entry) - VEHICLE_KEYS)
    if unknown:
        _fail(path, "%s.%s" % (where, unknown[0]), "unknown key (known: %s)" % ", ".join(sorted(VEHICLE_KEYS)))
    for key in ("name", "model", "urdf"):
        if key not in entry:
            _fail(path, "%s.%s" % (where, key), "missing")
    name = entry["name"]
    if not isinstance(name, str) or not re.fullmatch(r"[A-Za-z0-9_.-]+", name):
        _fail(path, where + ".name", "%r is not a name (letters, digits, _ . -)" % (name,))
    where = "vehicles[%s]" % name
    mass = entry.get("empty_mass_kg")
    if mass is not None and (not isinstance(mass, (int, float)) or isinstance(mass, bool) or not mass > 0):
        _fail(path, where + ".empty_mass_kg", "%r is not a positive mass in kg" % (mass,))
    return Vehicle(
        name=name,
        model=_file(path, folder, where + ".model", entry["model"]),
        urdf=_file(path, folder, where + ".urdf", entry["urdf"]),
        reference=_file(path, folder, where + ".reference", entry["reference"]) if "reference" in entry else None,
        empty_mass_kg=float(mass) if mass is not None else None,
        params=_file(path, folder, where + ".params", entry["params"]) if "params" in entry else None,
        logs=_patterns(path, folder, where + ".logs", entry["logs"]) if "logs" in entry else [],
        pack=str(entry["pack"]) if "pack" in entry else None,
        pack_pattern=_pattern(path, where + ".pack_pattern", entry["pack_pattern"]) if "pack_pattern" in entry else None)


def load(path):
    """The fleet in the description at `path`; DescriptionError for one that cannot be used."""
    try:
        with open(path) as handle:
            root = yaml.safe_load(handle)
    except OSError as error:
        raise DescriptionError("%s: cannot be read (%s)" % (path, error.strerror))
    except yaml.YAMLError as error:
        raise DescriptionError("%s: not YAML (%s)" % (path, str(error).replace("\n", " ")))
    if not isinstance(root, dict):
        raise DescriptionError("%s: expected a mapping with vehicles:, got %r" % (path, type(root).__name__))
    unknown = sorted(set(root) - FLEET_KEYS)
    if unknown:
        _fail(path, unknown[0], "unknown key (known: %s)" % ", ".join(sorted(FLEET_KEYS)))
    if not isinstance(root.get("vehicles"), list) or not root["vehicles"]:
        _fail(path, "vehicles", "expected a list of vehicles, got %r" % (root.get("vehicles"),))
    folder = os.path.dirname(os.path.abspath(path))
    vehicles = {}
    for index, entry in enumerate(root["vehicles"]):
        vehicle = _vehicle(path, folder, index, entry)
        if vehicle.name in vehicles:
            _fail(path, "vehicles[%d].name" % index, "'%s' is given twice" % vehicle.name)
        vehicles[vehicle.name] = vehicle
    logs = _patterns(path, folder, "logs", root["logs"]) if "logs" in root else []
    # Checked whenever given: a pattern kept for logs to come is refused now, not on their first run.
    vehicle_pattern = None
    if "vehicle_pattern" in root:
        vehicle_pattern = _pattern(path, "vehicle_pattern", root["vehicle_pattern"], group="vehicle")
    if logs and vehicle_pattern is None:
        _fail(path, "vehicle_pattern", "missing: the fleet's logs need the pattern that names a log's vehicle")
    for key in ("database", "report"):
        if key in root and (not isinstance(root[key], str) or not root[key]):
            _fail(path, key, "expected a path, got %r" % (root[key],))
    band = root.get("healthy_band", 0.05)
    if not isinstance(band, (int, float)) or isinstance(band, bool) or not 0.005 <= band <= 0.5:
        _fail(path, "healthy_band", "%r is outside 0.005..0.5 (a share of the rotor's thrust)" % (band,))
    return Fleet(path=path, vehicles=vehicles, logs=logs, vehicle_pattern=vehicle_pattern,
                 pack_pattern=_pattern(path, "pack_pattern", root["pack_pattern"]) if "pack_pattern" in root else None,
                 database=os.path.join(folder, root.get("database", "fleet.sqlite")),
                 report=os.path.join(folder, root.get("report", "fleet_report")), healthy_band=float(band))


def natural_key(text):
    """A sort key that puts "flight_2" before "flight_10"."""
    return [int(part) if part.isdigit() else part for part in re.split(r"(\d+)", text)]


def _expand(patterns):
    found = set()
    for pattern in patterns:
        found.update(p for p in glob.glob(pattern) if os.path.isfile(p))
    return found


def _pack_of(log, fixed, patterns):
    if fixed is not None:
        return fixed
    for pattern in patterns:
        if pattern is None:
            continue
        match = pattern.search(os.path.basename(log))
        if match:
            return match.group("pack") if "pack" in pattern.groupindex else match.group(1)
    return None


def logs(fleet):
    """Every log the description points at, as (vehicle name, log path, pack or None, problem or
    None), in the vehicle's flight order (natural order of the log names). A fleet-level log whose
    vehicle the pattern does not name, or names but the description does not hold, has its problem."""
    out = []
    for vehicle in fleet.vehicles.values():
        for log in _expand(vehicle.logs):
            out.append((vehicle.name, log, _pack_of(log, vehicle.pack, (vehicle.pack_pattern, fleet.pack_pattern)), None))
    for log in _expand(fleet.logs):
        match = fleet.vehicle_pattern.search(os.path.basename(log))
        if not match:
            out.append(("", log, None, "its name does not match vehicle_pattern '%s'" % fleet.vehicle_pattern.pattern))
            continue
        name = match.group("vehicle")
        vehicle = fleet.vehicles.get(name)
        if vehicle is None:
            out.append((name, log, None, "vehicle '%s' is not in the fleet description" % name))
            continue
        out.append((name, log, _pack_of(log, vehicle.pack, (vehicle.pack_pattern, fleet.pack_pattern)), None))
    unique = {}
    for row in out:
        unique.setdefault((row[0], row[1]), row)
    return sorted(unique.values(), key=lambda row: (row[0], natural_key(os.path.basename(row[1])), row[1]))
