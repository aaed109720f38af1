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


def last_line(text):
    """The last non-blank line of a tool's output: its one-line reason."""
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
            if motor.get("thrust_gap") is None or motor.get("thrust_gap_std") is None:
                continue  # not judged (a NaN is an absent key)
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
    """The row of one log (see _estimate_flight); whatever goes wrong becomes its refused row, so
    that one log never stops a run."""
    try:
        return _estimate_flight(job)
    except Exception as error:  # noqa: BLE001: any failure is this log's one line
        return _refused(job, "fleet could not estimate it: %s: %s" % (type(error).__name__, error),
                        job.get("digest") or "unreadable:" + job["log"])


def estimate_inputs(estimate, model, urdf, params, empty_mass_kg):
    """The estimate command line's vehicle part, the same for a log's estimate and for the fleet's
    `--check` of the vehicle (run.py): what one accepts, the other does."""
    command = [estimate, "--model", model, "--urdf", urdf]
    if params:
        command += ["--params", params]
    if empty_mass_kg is not None:
        command += ["--empty-mass-kg", repr(empty_mass_kg)]
    return command


def _estimate_flight(job):
    """The row of one log. `job`: vehicle, log, pack (or None), estimate (the tool), model, urdf,
    params (or None), empty_mass_kg (or None), reference ('vehicle' or 'none'), problem (a log
    refused before it is run, or None), digest (its content's, when the caller read it already)."""
    try:
        digest = job.get("digest")
        if not digest or digest.startswith("unreadable:"):
            digest = sha256(job["log"])
    except OSError as error:
        # Kept by its path: a log that cannot be read has no content to know it by.
        return _refused(job, "cannot be read (%s)" % error.strerror, "unreadable:" + job["log"])
    if job.get("problem"):
        return _refused(job, job["problem"], digest)
    with tempfile.TemporaryDirectory(prefix="fleet-") as out:
        command = estimate_inputs(job["estimate"], job["model"], job["urdf"], job.get("params"),
                                  job.get("empty_mass_kg")) + ["--out", out, "--no-figures", "--sample-rate-hz", "1",
                                                               job["log"]]
        done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        records = glob.glob(os.path.join(out, "*", "flight.yaml"))
        if done.returncode != 0 or len(records) != 1:
            return _refused(job, last_line(done.stderr or done.stdout), digest)
        with open(records[0]) as handle:
            record = yaml.safe_load(handle)
    return row_of(job, digest, record)
