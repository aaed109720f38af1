"""fleet on a small simulated fleet: the same rows whatever runs the tasks (one local worker, two,
a two-worker Dask LocalCluster); a run killed mid-way and restarted keeps every flight exactly
once and none half-written; bad logs, an unknown vehicle and a reference that does not match the
vehicle each give one line in the database and the report while the run goes on."""
import os
import random
import shutil
import signal
import sqlite3
import subprocess
import time

import yaml
from conftest import fleet_command, variant

from fleet_lib import database


def rows(path):
    connection = database.connect(path)
    try:
        flights = database.flights(connection)
    finally:
        connection.close()
    for flight in flights:
        del flight["id"]
    return sorted(flights, key=lambda f: (f["vehicle"], f["log"]))


def logs_in(folder):
    return sorted(os.listdir(os.path.join(folder, "logs")))


def test_one_worker_two_workers_and_a_dask_cluster_give_the_same_rows(small_fleet):
    from distributed import LocalCluster
    one = variant(small_fleet, "jobs1", database="jobs1.sqlite", report="jobs1_report")
    two = variant(small_fleet, "jobs2", database="jobs2.sqlite", report="jobs2_report")
    dask = variant(small_fleet, "dask", database="dask.sqlite", report="dask_report")
    subprocess.run(fleet_command(one, "--jobs", "1", "--quiet"), check=True)
    subprocess.run(fleet_command(two, "--jobs", "2", "--quiet"), check=True)
    # On the loopback interface, so that the cluster does not depend on the host name resolving
    # (containers, fresh CI machines; the ROS tests set ROS_HOSTNAME=localhost for the same reason).
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                      host="127.0.0.1") as cluster:
        subprocess.run(fleet_command(dask, "--scheduler", cluster.scheduler_address, "--quiet"), check=True)
    first = rows(os.path.join(small_fleet, "jobs1.sqlite"))
    assert len(first) == len(logs_in(small_fleet)) == 18
    assert all(f["status"] == "estimated" and len(f["rotors"]) == 4 and f["hovers"] for f in first)
    assert first == rows(os.path.join(small_fleet, "jobs2.sqlite"))
    assert first == rows(os.path.join(small_fleet, "dask.sqlite"))
    engines = sqlite3.connect(os.path.join(small_fleet, "dask.sqlite")).execute("SELECT engine FROM runs").fetchall()
    assert engines[0][0].startswith("dask tcp://")
    # A second run finds nothing new and changes nothing.
    subprocess.run(fleet_command(one, "--quiet"), check=True)
    assert rows(os.path.join(small_fleet, "jobs1.sqlite")) == first


def test_a_run_killed_mid_way_and_restarted_keeps_every_flight_exactly_once(small_fleet):
    path = variant(small_fleet, "killed", database="killed.sqlite", report="killed_report")
    whole = variant(small_fleet, "whole", database="whole.sqlite", report="whole_report")
    subprocess.run(fleet_command(whole, "--jobs", "2", "--quiet"), check=True)
    rng = random.Random(7)
    endings = []
    for kill in range(4):
        # Killed (SIGKILL, no clean-up) at a random moment after its first flight was written: a
        # write may be under way.
        process = subprocess.Popen(fleet_command(path, "--jobs", "2"), stdout=subprocess.PIPE, text=True,
                                   start_new_session=True)
        for line in process.stdout:
            if line.startswith("["):
                time.sleep(rng.uniform(0.0, 0.4))
                os.killpg(process.pid, signal.SIGKILL)
                break
        process.stdout.close()
        endings.append(process.wait())
    # The first run has all 18 flights before it and is always killed; a later run left with a
    # flight or two may finish inside the pause on a fast machine, and then it ends cleanly.
    assert endings[0] == -signal.SIGKILL
    assert all(ending in (-signal.SIGKILL, 0) for ending in endings)
    kept = rows(os.path.join(small_fleet, "killed.sqlite"))
    assert 4 <= len(kept) <= 18
    assert all(len(f["rotors"]) == 4 and f["hovers"] for f in kept)  # none half-written
    subprocess.run(fleet_command(path, "--quiet"), check=True)
    kept = rows(os.path.join(small_fleet, "killed.sqlite"))
    assert sorted(os.path.basename(f["log"]) for f in kept) == logs_in(small_fleet)
    assert kept == rows(os.path.join(small_fleet, "whole.sqlite"))


def test_bad_logs_an_unknown_vehicle_and_a_mismatched_reference_are_one_line_each(small_fleet, tmp_path):
    folder = str(tmp_path)
    for name in ("model.yaml", "f450_quad.urdf", "node_params.yaml", "fleet.yaml"):
        shutil.copy(os.path.join(small_fleet, name), folder)
    for vehicle in ("v01", "v02", "v03"):
        os.symlink(os.path.join(small_fleet, vehicle), os.path.join(folder, vehicle))
    os.mkdir(os.path.join(folder, "logs"))
    for log in logs_in(small_fleet):
        os.symlink(os.path.join(small_fleet, "logs", log), os.path.join(folder, "logs", log))
    with open(os.path.join(small_fleet, "logs", "v01_flight_001_pack-v01A.ulg"), "rb") as handle:
        whole = handle.read()
    with open(os.path.join(folder, "logs", "v01_flight_007_pack-v01A.ulg"), "wb") as handle:
        handle.write(whole[:len(whole) // 3])  # truncated mid-flight
    with open(os.path.join(folder, "logs", "v01_flight_008_pack-v01B.ulg"), "wb") as handle:
        handle.write(bytes(range(256)) * 64)  # of no known format
    with open(os.path.join(folder, "logs", "v99_flight_001_pack-v99A.ulg"), "wb") as handle:
        handle.write(whole)  # a vehicle the description does not hold
    # v03's model carries a reference of six rotors: it does not match its four motors.
    with open(os.path.join(folder, "model.yaml")) as handle:
        model = yaml.safe_load(handle)
    model["motor_reference"] = {"flights": 3, "shares": [1 / 6.0] * 6, "share_std": [0.001] * 6,
                                "gap_std": [0.002] * 6}
    with open(os.path.join(folder, "hexa_reference_model.yaml"), "w") as handle:
        yaml.safe_dump(model, handle)
    with open(os.path.join(folder, "fleet.yaml")) as handle:
        fleet = yaml.safe_load(handle)
    fleet["vehicles"][2] = {"name": "v03", "model": "hexa_reference_model.yaml", "urdf": "f450_quad.urdf"}
    # v02's reference names a flight that is not there: it cannot be learned.
    with open(os.path.join(small_fleet, "v02", "reference.manifest.yaml")) as handle:
        manifest = yaml.safe_load(handle)
    manifest["flights"][0]["log"] = "lost_flight.ulg"
    os.mkdir(os.path.join(folder, "v02_broken"))
    for name in os.listdir(os.path.join(small_fleet, "v02")):
        os.symlink(os.path.join(small_fleet, "v02", name), os.path.join(folder, "v02_broken", name))
    with open(os.path.join(folder, "v02_broken", "broken.manifest.yaml"), "w") as handle:
        yaml.safe_dump(manifest, handle)
    fleet["vehicles"][1]["reference"] = "v02_broken/broken.manifest.yaml"
    with open(os.path.join(folder, "fleet.yaml"), "w") as handle:
        yaml.safe_dump(fleet, handle)
    done = subprocess.run(fleet_command(os.path.join(folder, "fleet.yaml"), "--jobs", "2", "--quiet"),
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # v02 (its reference) and v03 (its model) cannot be judged at all: the run fails for them;
    # v01's bad files among its good ones and the unknown v99 are rows, not failures.
    assert done.returncode == 1, done.stdout + done.stderr
    unjudged = [line for line in done.stderr.splitlines() if "of its logs refused" in line]
    assert [line.split(" (")[0] for line in unjudged] == ["fleet: vehicle v02: all 6 of its logs refused",
                                                         "fleet: vehicle v03: all 6 of its logs refused"], done.stderr
    kept = {os.path.basename(f["log"]): f for f in rows(os.path.join(folder, "fleet.sqlite"))}
    assert len(kept) == 18 + 3
    truncated = kept["v01_flight_007_pack-v01A.ulg"]
    assert truncated["status"] == "damaged" and "truncated" in truncated["problem"]
    garbage = kept["v01_flight_008_pack-v01B.ulg"]
    assert garbage["status"] == "refused" and "format" in garbage["problem"], garbage["problem"]
    unknown = kept["v99_flight_001_pack-v99A.ulg"]
    assert unknown["status"] == "refused" and unknown["problem"] == "vehicle 'v99' is not in the fleet description"
    mismatched = [f for name, f in kept.items() if name.startswith("v03_")]
    assert len(mismatched) == 6
    assert all(f["status"] == "refused" and "motor_reference.shares: 6 shares for 4 rotors" in f["problem"]
               for f in mismatched), mismatched[0]["problem"]
    unlearned = [f for name, f in kept.items() if name.startswith("v02_")]
    assert len(unlearned) == 6
    assert all(f["status"] == "refused" and f["problem"].startswith("vehicle v02: its reference ") and
               "could not be learned: " in f["problem"] for f in unlearned), unlearned[0]["problem"]
    assert all(f["status"] == "estimated" for name, f in kept.items()
               if name.startswith("v01_") and "007" not in name and "008" not in name)
    with open(os.path.join(folder, "fleet_report", "README.md")) as handle:
        report = handle.read()
    problems = report.split("## Logs with problems")[1]
    for flight in [truncated, garbage, unknown] + mismatched + unlearned:
        assert flight["problem"] in problems
        assert "\n" not in flight["problem"]


def test_a_vehicle_whose_logs_are_all_refused_fails_the_run_until_mended(small_fleet, tmp_path):
    """A misspelt key in the vehicle's parameters refuses every log: the run says so in its status
    and one line, the next run tries the logs again, and once mended a bad file among the good logs
    no longer fails it."""
    folder = str(tmp_path)
    for name in ("model.yaml", "f450_quad.urdf"):
        shutil.copy(os.path.join(small_fleet, name), folder)
    with open(os.path.join(small_fleet, "node_params.yaml")) as handle:
        params = yaml.safe_load(handle)
    params["hover_typo"] = 1.0
    with open(os.path.join(folder, "node_params.yaml"), "w") as handle:
        yaml.safe_dump(params, handle)
    os.mkdir(os.path.join(folder, "logs"))
    logs = [log for log in logs_in(small_fleet) if log.startswith("v01_")][:2]
    for log in logs:
        os.symlink(os.path.join(small_fleet, "logs", log), os.path.join(folder, "logs", log))
    with open(os.path.join(folder, "fleet.yaml"), "w") as handle:
        yaml.safe_dump({"vehicles": [{"name": "v01", "model": "model.yaml", "urdf": "f450_quad.urdf",
                                      "params": "node_params.yaml", "logs": ["logs/*.ulg"]}]}, handle)
    def run():
        return subprocess.run(fleet_command(os.path.join(folder, "fleet.yaml"), "--quiet", "--no-report"),
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    for _ in range(2):
        done = run()
        assert done.returncode == 1, done.stdout + done.stderr
        assert "fleet: 2 new flights (2 refused)" in done.stdout, done.stdout
        assert "fleet: vehicle v01: all 2 of its logs refused (%s: " % logs[0] in done.stderr, done.stderr
    kept = rows(os.path.join(folder, "fleet.sqlite"))
    assert [f["status"] for f in kept] == ["refused", "refused"]
    assert all("hover_typo" in f["problem"] for f in kept), [f["problem"] for f in kept]
    del params["hover_typo"]
    with open(os.path.join(folder, "node_params.yaml"), "w") as handle:
        yaml.safe_dump(params, handle)
    with open(os.path.join(folder, "logs", "v01_flight_099_pack-v01A.ulg"), "wb") as handle:
        handle.write(b"not a log")
    done = run()
    assert done.returncode == 0, done.stdout + done.stderr
    assert "fleet: 3 new flights (1 refused)" in done.stdout, done.stdout
    assert run().returncode == 0  # the bad file tried again alone
    # A typo made once every good log is kept (only the bad file is tried again): the run fails and
    # names it, and passes again once it is mended.
    params["hover_typo"] = 1.0
    with open(os.path.join(folder, "node_params.yaml"), "w") as handle:
        yaml.safe_dump(params, handle)
    done = run()
    assert done.returncode == 1, done.stdout + done.stderr
    assert "fleet: 1 new flights (1 refused)" in done.stdout, done.stdout
    assert ("fleet: vehicle v01: its model, URDF and params cannot be estimated with: estimate: %s: hover_typo: "
            "unknown parameter" % os.path.join(folder, "node_params.yaml")) in done.stderr, done.stderr
    del params["hover_typo"]
    with open(os.path.join(folder, "node_params.yaml"), "w") as handle:
        yaml.safe_dump(params, handle)
    assert run().returncode == 0
