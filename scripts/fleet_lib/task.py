"""One log, one task: the offline estimate (`estimate`, the node's onboard session) of a log with
its vehicle's model, and its rotors judged against the vehicle's healthy reference. A plain
function of plain values, so that it runs the same in a thread, a process or on a Dask worker;
what it returns is the flight's row, and nothing in it depends on where it ran."""
import datetime
import glob
import hashlib
import math
import os
import subprocess
import tempfile

import yaml

# The 90 % interval of a rotor factor: +-1.645 standard deviations.
Z90 = 1.6448536269514722


def sha256(path):
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def log_time(path):
    """The log file's modification time, UTC, ISO 8601; None when it cannot be read."""
    try:
        stamp = os.stat(path).st_mtime
    except OSError:
        return None
    return datetime.datetime.fromtimestamp(stamp, datetime.timezone.utc).isoformat(timespec="seconds")


def _refused(job, problem, digest):
    return dict(vehicle=job["vehicle"], log=job["log"], log_sha256=digest, log_time_utc=log_time(job["log"]),
                pack=job.get("pack"), status="refused",
                problem=problem, reference=job.get("reference", "none"), duration_s=None, hover_mass_kg=None, pack_resistance_ohm=None,
                pack_resistance_std_ohm=None, supply_resistance_ohm=None, esc_verdict=None, flagged_channel=None,
                warnings=[], hovers=[], rotors=[])


def _last_line(text):
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    return lines[-1] if lines else "no output"


def _number(value):
    return None if value is None or (isinstance(value, float) and math.isnan(value)) else float(value)


def row_of(job, digest, record):
    """The flight's row from estimate's flight.yaml (`record`, parsed)."""
    health = record["motor_health"]
    rotors = []
    if health["judged"]:
        for motor in health["motors"]:
            factor = 1.0 - motor["thrust_gap"]
            std = motor["thrust_gap_std"]
            rotors.append(dict(channel=motor["channel"], factor=factor, factor_std=std,
                               factor_low=factor - Z90 * std, factor_high=factor + Z90 * std))
    masses = [h["total_mass_kg"] for h in record["hovers"] if h.get("total_mass_kg") is not None]
    warnings = list(record["warnings"])
    if not health["judged"]:
        warnings.append("rotors not judged: " + health.get("unavailable", "no full window of steady hover"))
    pack = record["pack"]
    esc = record["esc"]
    damage = record.get("log_damage") or None
    return dict(vehicle=job["vehicle"], log=job["log"], log_sha256=digest, log_time_utc=log_time(job["log"]),
                pack=job.get("pack"), status="damaged" if damage else "estimated", problem=damage, reference=job["reference"],
                duration_s=float(record["duration_s"]),
                hover_mass_kg=sum(masses) / len(masses) if masses else None,
                pack_resistance_ohm=_number(pack.get("internal_resistance_ohm")),
                pack_resistance_std_ohm=_number(pack.get("internal_resistance_std_ohm")),
                supply_resistance_ohm=_number(esc.get("supply_resistance_ohm")), esc_verdict=esc["verdict"],
                flagged_channel=health["flagged_channel"], warnings=warnings,
                hovers=[dict(start_s=h["start_s"], end_s=h["end_s"], total_mass_kg=h.get("total_mass_kg"),
                             payload_kg=h.get("payload_kg")) for h in record["hovers"]],
                rotors=rotors)


def estimate_flight(job):
    """The row of one log. `job`: vehicle, log, pack (or None), estimate (the tool), model, urdf,
    params (or None), empty_mass_kg (or None), reference ('vehicle' or 'none'), rotors (the
    reference's, or None), problem (a log refused before it is run, or None). Never raises for a bad
    log: its row is refused with one line."""
    try:
        digest = sha256(job["log"])
    except OSError as error:
        # Kept by its path: a log that cannot be read has no content to know it by.
        return _refused(job, "cannot be read (%s)" % error.strerror, "unreadable:" + job["log"])
    if job.get("problem"):
        return _refused(job, job["problem"], digest)
    with tempfile.TemporaryDirectory(prefix="fleet-") as out:
        command = [job["estimate"], "--model", job["model"], "--urdf", job["urdf"], "--out", out, "--no-figures",
                   "--sample-rate-hz", "1", job["log"]]
        if job.get("params"):
            command += ["--params", job["params"]]
        if job.get("empty_mass_kg") is not None:
            command += ["--empty-mass-kg", repr(job["empty_mass_kg"])]
        done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        records = glob.glob(os.path.join(out, "*", "flight.yaml"))
        if len(records) != 1:
            return _refused(job, _last_line(done.stderr or done.stdout), digest)
        with open(records[0]) as handle:
            record = yaml.safe_load(handle)
    row = row_of(job, digest, record)
    if job.get("rotors") is not None and row["rotors"] and len(row["rotors"]) != job["rotors"]:
        return _refused(job, "the log's %d motors do not match the reference's %d" % (len(row["rotors"]), job["rotors"]),
                        digest)
    return row
