#!/usr/bin/python3
"""Writes docs/BENCHMARKS.md (make bench) from the template and the figures scripts/run_benchmarks.sh left
in its results directory: the google benchmark JSON files (bench_<name>.json), the end-to-end and
callgrind JSON of scripts/bench_node.py (e2e.json, callgrind.json), scripts/bench_diagnose_gap.sh's
diagnose_gap.json and scripts/bench_diagnose_ulog.sh's diagnose_ulog.json, the commands run (commands.tsv: section, tab, command), the start date, the load
averages, the commit measured and the run time (started_utc.txt, load_start.txt, load_end.txt,
commit.txt, runtime_s.txt).

The template's placeholders are {{key}}; an unknown key is an error, a part that was not run
(make bench QUICK=1 skips diagnose_gap) is written as not measured. The arm64 section is the
fragment --arm64 (docs/BENCHMARKS.arm64.md) when that file exists.

Usage: scripts/write_benchmarks.py --results DIR --template FILE --arm64 FILE --out FILE [--make-command TEXT]
"""
import argparse
import json
import os
import re
import subprocess
import sys

NOT_MEASURED = "not measured in this run"
SYSTEM_NAMES = {"node": "estimator_node (defaults: publishes at 50 Hz)",
                "node_every_message": "estimator_node, `publish_rate_hz: 0` (publishes every message)",
                "floor": "transport floor (roscpp, does nothing; spinner thread)",
                "floor_inline": "transport floor, received in roscpp's network thread",
                "peer": "rospy peer (numpy)"}


class Results:
    def __init__(self, directory):
        self.directory = directory

    def path(self, name):
        return os.path.join(self.directory, name)

    def json(self, name):
        if not os.path.exists(self.path(name)):
            return None
        with open(self.path(name)) as f:
            return json.load(f)

    def text(self, name):
        if not os.path.exists(self.path(name)):
            return None
        with open(self.path(name)) as f:
            return f.read().strip()

    def commands(self):
        commands = {}
        for line in (self.text("commands.tsv") or "").splitlines():
            section, _, command = line.partition("\t")
            commands[section] = command
        return commands

    def benchmark(self, binary, name):
        document = self.json(binary + ".json")
        if document is None:
            return None
        for entry in document["benchmarks"]:
            if entry["name"] == name and entry.get("run_type", "iteration") == "iteration":
                return entry
        raise SystemExit("write_benchmarks.py: %s has no benchmark %s" % (self.path(binary + ".json"), name))


def format_seconds(seconds):
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("µs", 1e-6)):
        if seconds >= scale:
            return "%.3g %s" % (seconds / scale, unit)
    return "%.3g ns" % (seconds / 1e-9)


UNIT_SECONDS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def benchmark_seconds(entry):
    return entry["real_time"] * UNIT_SECONDS[entry["time_unit"]]


def number(value, digits=3):
    return "n/a" if value is None else "%.*g" % (digits, value)


def e2e_table(e2e):
    if e2e is None:
        return NOT_MEASURED + "."
    lines = ["| system | RCOut sent / handled | latency p50 | p99 | max | CPU (% of one core): all, each round | "
             "RSS start → end |",
             "|---|---:|---:|---:|---:|---:|---:|"]
    for row in e2e["systems"]:
        lines.append("| %s | %d / %d | %s | %s | %s | %.2f %% (%s) | %.1f → %.1f MB |" % (
            SYSTEM_NAMES[row["system"]], row["rc_out_sent"], row["handled"],
            *("n/a" if row[key] is None else "%.2f ms" % row[key]
              for key in ("latency_p50_ms", "latency_p99_ms", "latency_max_ms")),
            row["cpu_percent"], " / ".join("%.2f" % c for c in row["cpu_percent_rounds"]),
            row["rss_start_kb"] / 1024.0, row["rss_end_kb"] / 1024.0))
    return "\n".join(lines)


def ratio(numerator, denominator):
    if numerator is None or denominator is None or denominator == 0:
        return "n/a"
    return "%.2f" % (numerator / denominator)


def e2e_ratios(e2e):
    if e2e is None:
        return ""
    systems = {row["system"]: row for row in e2e["systems"]}
    lines = ["| ratio | CPU | RSS at the end | latency p50 | latency p99 |", "|---|---:|---:|---:|---:|"]
    for label, top, bottom in (("node / floor", "node", "floor"),
                               ("node / floor received in the network thread", "node", "floor_inline"),
                               ("node publishing every message / floor", "node_every_message", "floor"),
                               ("peer / node", "peer", "node")):
        if top not in systems or bottom not in systems:
            continue
        a, b = systems[top], systems[bottom]
        lines.append("| %s | %s | %s | %s | %s |" % (
            label, ratio(a["cpu_percent"], b["cpu_percent"]), ratio(a["rss_end_kb"], b["rss_end_kb"]),
            ratio(a["latency_p50_ms"], b["latency_p50_ms"]), ratio(a["latency_p99_ms"], b["latency_p99_ms"])))
    lines.append("")
    lines.append("The floors answer nothing: their latency ratios are n/a.")
    return "\n".join(lines)


def e2e_commands(e2e, commands, repo):
    if e2e is None:
        return NOT_MEASURED + "."
    lines = ["- `%s`" % commands.get("e2e", "?")]
    for row in e2e["systems"]:
        lines.append("- %s: `%s`" % (row["system"], row["command"].replace(repo + os.sep, "")))
    return "\n".join(lines)


def callgrind_table(callgrind):
    if callgrind is None:
        return NOT_MEASURED + "."
    parts = callgrind["instructions_per_message"]
    total = parts["total"]
    rows = [("decoding", "`RcOutDecoder::decode`: the ShapeShifter's bytes to channels and stamp"),
            ("estimation", "`Estimator::addMotorOutputs`: surfaces, checks, hover and payload windows"),
            ("publishing", "`EstimatorNode::publish`: filling and publishing ~motors, ~totals, ~payload"),
            ("total", "`EstimatorNode::onRcOut`: all of it, with counters and the clock")]
    lines = ["| part | instructions per message | share | what |", "|---|---:|---:|---|"]
    for part, what in rows:
        lines.append("| %s | %s | %.0f %% | %s |" % (part, "{:,.0f}".format(parts[part]), 100.0 * parts[part] / total,
                                                    what))
    esc = callgrind.get("with_esc_telemetry")
    if esc:
        esc_total = esc["instructions_per_message"]["total"]
        lines += ["", "With ESC telemetry (`mavros_msgs/ESCTelemetry` at %g Hz, %d ESCs in each message, %d decoded "
                  "after the warm-up; the same RCOut load):" % (esc["esc_rate_hz"], esc["escs"], esc["esc_handled"]),
                  "", "| callback | instructions per message | against no telemetry |", "|---|---:|---:|",
                  "| `EstimatorNode::onRcOut`, per RCOut | %s | %+.1f %% |" % (
                      "{:,.0f}".format(esc_total), 100.0 * (esc_total / total - 1.0)),
                  "| `EstimatorNode::onEscTelemetry`, per ESCTelemetry (decoding and the live model check) | %s | |" % (
                      "{:,.0f}".format(esc["esc_instructions_per_message"]))]
    return "\n".join(lines)


def diagnose_gap_table(gap):
    if gap is None:
        return NOT_MEASURED + " (make bench QUICK=1 skips it)."
    lines = ["%d MB of uncompressed bags, %s messages (/sim/truth included)." % (gap["bags_mb"],
                                                                                "{:,}".format(gap["messages"])),
             "", "| `--jobs` | reading the bags | whole run | peak memory |", "|---|---:|---:|---:|"]
    for run in gap["runs"]:
        lines.append("| %d | %.2f s | %.2f s | %.0f MB |" % (run["jobs"], run["reading_s"], run["whole_s"],
                                                             run["peak_kb"] / 1024.0))
    return "\n".join(lines)


def diagnose_ulog_table(ulog):
    if ulog is None:
        return NOT_MEASURED + " (make bench QUICK=1 skips it)."
    lines = ["%d MB of ULog." % ulog["ulogs_mb"], "",
             "| tool | reading the logs | whole run | CPU time | peak memory |", "|---|---:|---:|---:|---:|",
             "| diagnose_gap | %.2f s | %.2f s | %.2f s | %.0f MB |" % (ulog["reading_s"], ulog["whole_s"], ulog["cpu_s"],
                                                                      ulog["peak_kb"] / 1024.0)]
    if "estimate_s" in ulog:
        lines.append("| estimate, one core | | %.2f s | %.2f s | %.0f MB |" % (
            ulog["estimate_s"], ulog["estimate_cpu_s"], ulog["estimate_peak_kb"] / 1024.0))
    return "\n".join(lines)


def fleet_table(fleet):
    if fleet is None:
        return NOT_MEASURED + " (make bench QUICK=1 skips it)."
    return "\n".join([
        "| flights | flight-hours | whole run, `--jobs 2` | CPU time | peak memory | flight-hours per core-second | "
        "1,000 flight-hours on 16 cores |", "|---:|---:|---:|---:|---:|---:|---:|",
        "| %d | %.2f | %.1f s | %.1f s | %.0f MB | %.4f | %.1f min |" % (
            fleet["flights"], fleet["flight_hours"], fleet["wall_s"], fleet["cpu_s"], fleet["peak_kb"] / 1024.0,
            fleet["hours_per_core_s"], fleet["minutes_1000h_16_cores"])])


def machine():
    info = {"cpu_model": "?", "cpu_mhz": "?", "memory": "?"}
    try:
        lscpu = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
        match = re.search(r"^Model name:\s*(.+)$", lscpu, re.M)
        if match:
            info["cpu_model"] = match.group(1).strip()
    except OSError:
        pass
    with open("/proc/cpuinfo") as f:
        cpuinfo = f.read()
    if info["cpu_model"] == "?":
        match = re.search(r"^model name\s*:\s*(.+)$", cpuinfo, re.M)
        info["cpu_model"] = match.group(1).strip() if match else "?"
    match = re.search(r"^cpu MHz\s*:\s*([\d.]+)$", cpuinfo, re.M)
    if match:
        info["cpu_mhz"] = "%.0f" % float(match.group(1))
    with open("/proc/meminfo") as f:
        match = re.search(r"^MemTotal:\s*(\d+) kB", f.read(), re.M)
    if match:
        info["memory"] = "%.1f GiB" % (int(match.group(1)) / 1024.0 ** 2)
    info["cpus"] = str(os.cpu_count())
    info["os"] = "?"
    if os.path.exists("/etc/os-release"):
        with open("/etc/os-release") as f:
            match = re.search(r'^PRETTY_NAME="?([^"\n]+)"?$', f.read(), re.M)
        if match:
            info["os"] = match.group(1)
    info["kernel"] = os.uname().release
    try:
        version = subprocess.run(["c++", "--version"], capture_output=True, text=True).stdout.splitlines()[0]
        info["compiler"] = version
    except (OSError, IndexError):
        info["compiler"] = "?"
    return info


def values(results, args):
    e2e = results.json("e2e.json")
    callgrind = results.json("callgrind.json")
    commands = results.commands()
    repo = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
    runtime = results.text("runtime_s.txt")
    v = dict(machine())
    v.update(make_command="`%s`" % args.make_command, date=results.text("started_utc.txt") or "?",
             commit=results.text("commit.txt") or "unknown", load_start=results.text("load_start.txt") or "?",
             load_end=results.text("load_end.txt") or "?",
             runtime="%d min %02d s" % divmod(int(runtime), 60) if runtime else "?",
             e2e_table=e2e_table(e2e), e2e_ratios=e2e_ratios(e2e), e2e_commands=e2e_commands(e2e, commands, repo),
             callgrind_table=callgrind_table(callgrind), diagnose_gap_table=diagnose_gap_table(
                 results.json("diagnose_gap.json")), diagnose_ulog_table=diagnose_ulog_table(
                 results.json("diagnose_ulog.json")), fleet_table=fleet_table(results.json("fleet.json")))
    for key in ("channels", "rate_hz", "battery_rate_hz", "duration_s", "rounds"):
        v[key] = number(e2e[key]) if e2e else "?"
    for key, field in (("callgrind_sent", "rc_out_sent"), ("callgrind_handled", "handled"),
                       ("callgrind_rate_hz", "rate_hz"), ("callgrind_warmup_s", "warmup_s"),
                       ("callgrind_published", "published"), ("callgrind_measured_s", "measured_s")):
        v[key] = number(callgrind[field], 6) if callgrind else "?"
    v["callgrind_command"] = callgrind["command"].replace(repo + os.sep, "") if callgrind else "?"
    quad = results.benchmark("bench_estimator", "BM_EstimatorRcOutMessage/4")
    octa = results.benchmark("bench_estimator", "BM_EstimatorRcOutMessage/8")
    if quad and octa:
        v["octa_share_50hz"] = "%.3f %%" % (100.0 * 50.0 * benchmark_seconds(octa))
        per_motor_s = (benchmark_seconds(octa) - benchmark_seconds(quad)) / 4.0
        v["per_motor"] = (format_seconds(per_motor_s) if per_motor_s > 0.0
                          else "nothing measurable in this run (the octa was not slower than the quad)")
    else:
        v["octa_share_50hz"] = v["per_motor"] = NOT_MEASURED
    if os.path.exists(args.arm64):
        with open(args.arm64) as f:
            v["arm64"] = f.read().strip()
    else:
        v["arm64"] = ("No arm64 figures in this run: `make bench` includes `%s` here when that file exists."
                      % os.path.basename(args.arm64))
    return v, commands


def render(template, results, args):
    v, commands = values(results, args)

    def substitute(match):
        key = match.group(1)
        kind, _, rest = key.partition(":")
        if kind == "command":
            return "`%s`" % commands[rest] if rest in commands else NOT_MEASURED
        if kind in ("gb", "gb_counter", "gb_rate"):
            binary, _, name = rest.partition(":")
            counter = None
            if kind == "gb_counter":
                name, _, counter = name.rpartition(":")
            entry = results.benchmark(binary, name)
            if entry is None:
                return NOT_MEASURED
            if kind == "gb":
                return format_seconds(benchmark_seconds(entry))
            if kind == "gb_rate":
                return "%.2g M" % (entry["items_per_second"] / 1e6)
            return "%.1f" % entry[counter]
        if key not in v:
            raise SystemExit("write_benchmarks.py: unknown placeholder {{%s}} in %s" % (key, args.template))
        return v[key]

    return re.sub(r"\{\{([^}]+)\}\}", substitute, template)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--results", required=True)
    parser.add_argument("--template", required=True)
    parser.add_argument("--arm64", required=True, help="Markdown fragment of the arm64 figures, included if present")
    parser.add_argument("--out", required=True)
    parser.add_argument("--make-command", default="make bench")
    args = parser.parse_args()
    with open(args.template) as f:
        template = f.read()
    text = render(template, Results(args.results), args)
    with open(args.out, "w") as f:
        f.write(text)


if __name__ == "__main__":
    sys.exit(main())
