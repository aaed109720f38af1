"""fleet's command line: every log of the description not kept yet is estimated (on --jobs local
workers or, with --scheduler, on a Dask distributed cluster), each finished flight written to the
database at once, then the trends and the report are made from everything the database holds."""
import argparse
import concurrent.futures
import datetime
import os
import shutil
import subprocess
import sys

from . import database, description, references, report, task


def _tool(name, given):
    """The package's tool `name`: --estimate/--diagnose-gap, else beside this script (the devel and
    install spaces put both in the package's lib folder), else on PATH."""
    if given:
        return given
    here = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
    for folder in (here, os.path.dirname(os.path.abspath(sys.argv[0]))):
        candidate = os.path.join(folder, name)
        if os.access(candidate, os.X_OK):
            return candidate
    found = shutil.which(name)
    if not found:
        raise SystemExit("fleet: cannot find the %s tool: give --%s" % (name, name.replace("_", "-")))
    return found


def _inputs_problem(vehicle, model, estimate):
    """None when `estimate --check` accepts the vehicle's model (with its reference), URDF, params
    and empty mass, else the line naming the vehicle: a params file mistyped after its logs were all
    estimated is heard of on the next run, not when a new log arrives. `estimate` None: not checked
    (the tool runs on the workers only)."""
    if estimate is None:
        return None
    command = task.estimate_inputs(estimate, model, vehicle.urdf, vehicle.params, vehicle.empty_mass_kg) + ["--check"]
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if done.returncode == 0:
        return None
    return "vehicle %s: its model, URDF and params cannot be estimated with: %s" % (
        vehicle.name, task.last_line(done.stderr or done.stdout))


def _reference_models(fleet, diagnose_gap, estimate, workers):
    """Each vehicle's model with its reference (learned on `workers` threads where a manifest is
    given), and one line for each vehicle whose reference could not be learned or whose inputs
    `estimate --check` refuses."""
    folder = os.path.dirname(os.path.abspath(fleet.database))

    def learn(vehicle):
        try:
            model = references.model_for(vehicle, folder, diagnose_gap, sys.executable)
            refused = _inputs_problem(vehicle, model, estimate)
            if refused:
                return vehicle.name, None, refused
            return vehicle.name, (model, references.motor_count(model) is not None), None
        except references.ReferenceError as error:
            return vehicle.name, None, str(error)
        except Exception as error:  # noqa: BLE001: one vehicle's model never stops the run
            return vehicle.name, None, "vehicle %s: its model or reference cannot be used: %s: %s" % (
                vehicle.name, type(error).__name__, error)

    with concurrent.futures.ThreadPoolExecutor(max_workers=workers) as pool:
        learned = list(pool.map(learn, fleet.vehicles.values()))
    return ({name: model for name, model, _ in learned if model},
            {name: problem for name, _, problem in learned if problem})


def jobs_for(fleet, connection, estimate, diagnose_gap, workers):
    """The tasks of every log not kept yet, and one line for each vehicle that cannot be judged
    (its reference not learned, its params refused)."""
    kept = database.seen(connection)
    # With a scheduler, --estimate may name the workers' tool: the vehicles are then checked there,
    # with each log, and this machine says so.
    checker = estimate if shutil.which(estimate) else None
    if checker is None:
        print("fleet: %s cannot be run here: each vehicle's inputs are checked with its logs only" % estimate,
              file=sys.stderr)
    models, problems = _reference_models(fleet, diagnose_gap, checker, workers)
    jobs = []
    for name, log, pack, problem in description.logs(fleet):
        try:
            digest = task.sha256(log)
        except OSError:
            digest = "unreadable:" + log
        # A log kept, or the same content found twice for one vehicle (the first in log order runs:
        # the same row whatever the engine).
        if (name, digest) in kept:
            continue
        kept.add((name, digest))
        job = dict(vehicle=name, log=log, digest=digest, pack=pack, estimate=estimate,
                   problem=problem or problems.get(name))
        vehicle = fleet.vehicles.get(name)
        if vehicle is not None and name in models:
            model, has_reference = models[name]
            job.update(model=model, urdf=vehicle.urdf, params=vehicle.params, empty_mass_kg=vehicle.empty_mass_kg,
                       reference="vehicle" if has_reference else "none")
        jobs.append(job)
    return jobs, problems


def _local(jobs, workers):
    # Each task is an estimate process: threads only wait on it.
    with concurrent.futures.ThreadPoolExecutor(max_workers=workers) as pool:
        futures = [pool.submit(task.estimate_flight, job) for job in jobs]
        for future in concurrent.futures.as_completed(futures):
            yield future.result()


def _dask(jobs, address):
    import cloudpickle
    from distributed import Client, as_completed
    # The workers need not have this package on their path: the task goes with its code.
    cloudpickle.register_pickle_by_value(task)
    with Client(address) as client:
        futures = client.map(task.estimate_flight, jobs, pure=False)
        for future in as_completed(futures):
            yield future.result()


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="fleet", description="Estimates every new flight of every vehicle of a fleet against its own healthy "
        "reference, keeps one row per flight in an SQLite database and reports the trends (docs/fleet.md).")
    parser.add_argument("description", help="the fleet description (YAML)")
    engine = parser.add_mutually_exclusive_group()
    engine.add_argument("--jobs", type=int, default=1, help="logs estimated in parallel on this machine (default 1)")
    engine.add_argument("--scheduler", help="a Dask distributed scheduler's address (tcp://host:8786): each log a task")
    parser.add_argument("--estimate", help="the estimate tool (default: the package's)")
    parser.add_argument("--diagnose-gap", help="the diagnose_gap tool, which learns references (default: the package's)")
    parser.add_argument("--no-report", action="store_true", help="update the database only")
    parser.add_argument("--quiet", action="store_true", help="no line per flight")
    args = parser.parse_args(argv)
    if args.jobs < 1:
        parser.error("--jobs: %d is not a number of workers (1 or more)" % args.jobs)
    try:
        fleet = description.load(args.description)
        connection = database.connect(fleet.database)
    except (description.DescriptionError, database.DatabaseError) as error:
        print("fleet: %s" % error, file=sys.stderr)
        return 2
    estimate = _tool("estimate", args.estimate)
    diagnose_gap = _tool("diagnose_gap", args.diagnose_gap)
    jobs, problems = jobs_for(fleet, connection, estimate, diagnose_gap, args.jobs)
    for line in problems.values():
        print("fleet: %s" % line, file=sys.stderr)
    engine_name = "dask %s" % args.scheduler if args.scheduler else "jobs %d" % args.jobs
    run_id = database.start_run(connection, datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
                                os.path.abspath(args.description), engine_name)
    rows = _dask(jobs, args.scheduler) if args.scheduler else _local(jobs, args.jobs)
    refused = 0
    for count, row in enumerate(rows, start=1):
        database.insert_flight(connection, row, run_id)
        refused += row["status"] == "refused"
        if not args.quiet:
            what = row["problem"] if row["status"] == "refused" else "%d hovers, %d rotors judged" % (
                len(row["hovers"]), len(row["rotors"]))
            print("[%d/%d] %s %s: %s" % (count, len(jobs), row["vehicle"] or "?", row["log"], what), flush=True)
    print("fleet: %d new flights (%d refused) in %s" % (len(jobs), refused, fleet.database))
    flights = database.flights(connection)
    if not args.no_report:
        written = report.write(fleet, flights, problems)
        print("fleet: report %s" % written)
    connection.close()
    unjudged = unjudged_vehicles(fleet, flights)
    for line in unjudged:
        print("fleet: %s" % line, file=sys.stderr)
    # A vehicle that cannot be judged fails the run even when all its logs were kept before.
    return 1 if unjudged or problems else 0


def unjudged_vehicles(fleet, flights):
    """One line for each vehicle of the description whose every kept log is refused: its parameters,
    model or reference are at fault rather than a log, and a scheduler should hear of it. A bad file
    among a vehicle's good logs is a row of the report, not a failed run."""
    by_vehicle = {}
    for flight in flights:
        if flight["vehicle"] in fleet.vehicles:
            by_vehicle.setdefault(flight["vehicle"], []).append(flight)
    lines = []
    for name in sorted(by_vehicle):
        kept = by_vehicle[name]
        if all(f["status"] == "refused" for f in kept):
            first = min(kept, key=lambda f: f["log"])
            lines.append("vehicle %s: all %d of its logs refused (%s: %s)" % (
                name, len(kept), os.path.basename(first["log"]), first["problem"]))
    return lines
