#!/usr/bin/python3
"""The node's end-to-end benchmarks (make bench): the same load on three systems under test, and
the instructions estimator_node spends per RCOut message.

e2e: bench_probe publishes mavros_msgs/RCOut (8 channels, hover PWM with noise, stamped now) at
--rate-hz and sensor_msgs/BatteryState at 1 Hz for --duration-s to, one after another,
  node                estimator_node with the thesis model and the 8-rotor
                      test/benchmark/bench_octo.urdf (publish_rate_hz: its default),
  node_every_message  the same with publish_rate_hz 0,
  floor               bench_floor_node, which receives the same topics and does nothing, the way
                      most roscpp nodes receive (roscpp's own cost),
  floor_inline        the same, receiving in roscpp's network thread as estimator_node does,
  peer                test/benchmark/rospy_peer.py, the same per-motor outputs in rospy with numpy,
and times every ~totals from the RCOut stamp it carries to its receipt, and reads the system's CPU
time and resident memory from /proc. Each system gets its own roscore on a free port (never 11311),
torn down after it. This is done --rounds times, every other round in the reverse order, so that a
drift of the machine's background load weighs on every system alike; a system's CPU share is its
CPU time over all its rounds' wall time, its latencies those of all its rounds.

callgrind: estimator_node under valgrind --tool=callgrind, collecting only inside
EstimatorNode::onRcOut, driven with RCOut at 100 Hz until its windows are full, then, counters
zeroed, with --callgrind-messages more; callgrind_annotate's inclusive counts of decoding,
estimation and publishing divided by the messages handled; then again with mavros_msgs/ESCTelemetry
at 50 Hz (every ESC in each message), its callback EstimatorNode::onEscTelemetry counted apart,
per ESCTelemetry decoded.

Writes one JSON file per part. Usage:
  scripts/bench_node.py --bin DIR --repo DIR --work DIR [--duration-s 60] [--rounds 2] [--systems node floor ...]
                        [--e2e-json F] [--callgrind-json F]
"""
import argparse
import json
import math
import os
import re
import signal
import socket
import subprocess
import sys
import time
import xmlrpc.client

import yaml

RC_OUT_CHANNELS = 8
ESTIMATE_TOPICS = {"node": "/propulsion_estimator/totals", "node_every_message": "/propulsion_estimator/totals",
                   "peer": "/rospy_peer/totals", "floor": "", "floor_inline": ""}
SYSTEMS = ("node", "node_every_message", "floor", "floor_inline", "peer")
# callgrind_annotate's names of the three parts of onRcOut (demangled, arguments stripped).
CALLGRIND_PARTS = [
    ("decoding", "propulsion_estimator::RcOutDecoder::decode"),
    ("estimation", "propulsion_estimator::Estimator::addMotorOutputs"),
    ("publishing", "propulsion_estimator::EstimatorNode::publish"),
]
CALLGRIND_TOTAL = "propulsion_estimator::EstimatorNode::onRcOut"
# The ESC telemetry callback and its decoder (the calls counted as messages).
CALLGRIND_ESC = "propulsion_estimator::EstimatorNode::onEscTelemetry"
CALLGRIND_ESC_DECODE = "propulsion_estimator::EscTelemetryDecoder::decode"
# mavros_msgs/ESCTelemetry per second, every ESC in each (ArduPilot's ESC_TELEMETRY_x at 50 Hz).
CALLGRIND_ESC_RATE_HZ = 50.0
# Longer than the parameter template's hover window (2 s) and payload averaging window (10 s).
CALLGRIND_WARMUP_S = 15.0


def free_port():
    """A port nothing listens on, never ROS's default 11311 (a master of someone else's may start there)."""
    while True:
        with socket.socket() as s:
            s.bind(("localhost", 0))
            port = s.getsockname()[1]
        if port != 11311:
            return port


class Master:
    """A roscore of its own on a free port, in its own process group; stopped on exit."""

    def __init__(self, work, name):
        self.port = free_port()
        self.uri = "http://localhost:%d" % self.port
        self.env = dict(os.environ, ROS_MASTER_URI=self.uri, ROS_HOSTNAME="localhost",
                        ROS_LOG_DIR=os.path.join(work, "log", name))
        self.log = open(os.path.join(work, "roscore_%s.log" % name), "w")
        self.process = subprocess.Popen(["roscore", "-p", str(self.port)], env=self.env, stdout=self.log,
                                        stderr=subprocess.STDOUT, start_new_session=True)
        self.proxy = xmlrpc.client.ServerProxy(self.uri)
        deadline = time.monotonic() + 60.0
        while True:
            try:
                self.proxy.getPid("/bench")
                return
            except OSError:
                if time.monotonic() > deadline or self.process.poll() is not None:
                    self.stop()
                    sys.exit("bench_node.py: roscore on port %d did not start (see %s)" % (self.port, self.log.name))
                time.sleep(0.2)

    def set_param(self, key, value):
        code, message, _ = self.proxy.setParam("/bench", key, value)
        if code != 1:
            sys.exit("bench_node.py: setting %s: %s" % (key, message))

    def stop(self):
        stop_group(self.process, signal.SIGINT, 20.0)
        self.log.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()


def stop_group(process, sig, timeout_s):
    """Stops a process started with start_new_session=True, and its children, by its group."""
    if process.poll() is None:
        os.killpg(process.pid, sig)
        try:
            process.wait(timeout_s)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()


def estimator_params(repo, every_message=False):
    """The parameter template with the benchmark's model and octocopter; every_message sets
    publish_rate_hz 0 (the default publishes at most at 50 Hz)."""
    with open(os.path.join(repo, "config", "estimator_params.yaml")) as f:
        params = yaml.safe_load(f)
    params.update(model=os.path.join(repo, "config", "e300_dji2212_dji9443.yaml"),
                  motor_channels=list(range(1, RC_OUT_CHANNELS + 1)),
                  urdf_file=os.path.join(repo, "test", "benchmark", "bench_octo.urdf"), tare_file="")
    if every_message:
        params.update(publish_rate_hz=0.0)
    return params


def system_command(system, args, master):
    if system in ("node", "node_every_message"):
        master.set_param("/propulsion_estimator", estimator_params(args.repo, system == "node_every_message"))
        return [os.path.join(args.bin, "estimator_node"), "__name:=propulsion_estimator"]
    if system == "peer":
        master.set_param("/rospy_peer", {"model": os.path.join(args.repo, "config", "e300_dji2212_dji9443.yaml"),
                                         "motor_channels": list(range(1, RC_OUT_CHANNELS + 1))})
        return ["/usr/bin/python3", os.path.join(args.repo, "test", "benchmark", "rospy_peer.py")]
    return [os.path.join(args.bin, "bench_floor_node")] + (["--inline"] if system == "floor_inline" else [])


def run_probe(args, master, name, rate_hz, duration_s, estimate_topic, system, pid, drain_s, on_load=None,
              esc_rate_hz=0.0):
    """Runs bench_probe against `system` (a Popen), which must live as long as the probe; calls
    on_load() once the load has started. Returns its JSON, with the latencies measured (ms, sorted)
    under "latencies_ms"."""
    out = os.path.join(args.work, "probe_%s.json" % name)
    latencies_file = os.path.join(args.work, "latencies_%s.txt" % name)
    command = [os.path.join(args.bin, "bench_probe"), "--duration-s", str(duration_s), "--rate-hz", str(rate_hz),
               "--channels", str(RC_OUT_CHANNELS), "--drain-s", str(drain_s), "--json", out,
               "--connect-timeout-s", "300"]
    if estimate_topic:
        command += ["--estimate-topic", estimate_topic, "--latencies-file", latencies_file]
    if pid:
        command += ["--pid", str(pid)]
    if esc_rate_hz:
        command += ["--esc-rate-hz", str(esc_rate_hz)]
    probe = subprocess.Popen(command, env=master.env, stdout=subprocess.PIPE, text=True)
    # The probe gives up on its own if nothing connects within its --connect-timeout-s.
    for line in probe.stdout:
        sys.stdout.write(line)
        if line.startswith("bench_probe: load started"):
            break
    if on_load:
        on_load()
    deadline = time.monotonic() + duration_s + 400.0
    while probe.poll() is None:
        if system.poll() is not None or time.monotonic() > deadline:
            probe.kill()
            probe.wait()
            sys.exit("bench_node.py: %s %s during the load (its log: %s)" % (
                name, "stopped" if system.poll() is not None else "timed out", args.work))
        time.sleep(0.2)
    if probe.returncode != 0:
        sys.exit("bench_node.py: bench_probe failed on %s (%s)" % (name, " ".join(command)))
    with open(out) as f:
        result = json.load(f)
    result["latencies_ms"] = []
    if estimate_topic:
        with open(latencies_file) as f:
            result["latencies_ms"] = [float(line) for line in f]
    return result


def run_system(args, system, round_index):
    """One round of the load on one system: its probe's JSON, plus what it handled and its command."""
    name = "%s_%d" % (system, round_index)
    print("== end to end: %s (round %d of %d), %g s at %g Hz" % (
        system, round_index + 1, args.rounds, args.duration_s, args.rate_hz), flush=True)
    with Master(args.work, name) as master:
        command = system_command(system, args, master)
        log = open(os.path.join(args.work, "%s.log" % name), "w+")
        process = subprocess.Popen(command, env=master.env, stdout=log, stderr=subprocess.STDOUT,
                                   start_new_session=True)
        try:
            probe = run_probe(args, master, name, args.rate_hz, args.duration_s, ESTIMATE_TOPICS[system],
                              process, process.pid, drain_s=2.0)
        finally:
            stop_group(process, signal.SIGINT, 20.0)
        log.seek(0)
        output = log.read()
        log.close()
    if ESTIMATE_TOPICS[system]:
        probe["handled"] = probe["estimates_received"]
    else:
        counts = re.search(r'\{"rc_out_received": (\d+), "battery_received": (\d+)\}', output)
        if not counts:
            sys.exit("bench_node.py: bench_floor_node printed no counts:\n" + output)
        probe["handled"] = int(counts.group(1))
    probe["command"] = " ".join(command)
    print("   sent %d, handled %d, latency p50 %s ms, CPU %.2f %%, RSS %d -> %d kB" % (
        probe["rc_out_sent"], probe["handled"], percentile(probe["latencies_ms"], 50.0), probe["cpu_percent"],
        probe["rss_start_kb"], probe["rss_end_kb"]), flush=True)
    return probe


def percentile(sorted_values, p):
    """The nearest-rank percentile of sorted values; None for no values."""
    if not sorted_values:
        return None
    rank = math.ceil(p / 100.0 * len(sorted_values))
    return sorted_values[min(len(sorted_values) - 1, max(rank, 1) - 1)]


def combine_rounds(system, rounds):
    """A system's row from its rounds: sums, CPU over all the wall time, latencies pooled; the memory
    of the round that grew most."""
    latencies = sorted(latency for r in rounds for latency in r["latencies_ms"])
    grew_most = max(rounds, key=lambda r: r["rss_end_kb"] - r["rss_start_kb"])
    return dict(system=system, command=rounds[0]["command"],
                rc_out_sent=sum(r["rc_out_sent"] for r in rounds), handled=sum(r["handled"] for r in rounds),
                cpu_percent=100.0 * sum(r["cpu_s"] for r in rounds) / sum(r["wall_s"] for r in rounds),
                cpu_percent_rounds=[r["cpu_percent"] for r in rounds],
                latency_p50_ms=percentile(latencies, 50.0), latency_p99_ms=percentile(latencies, 99.0),
                latency_max_ms=latencies[-1] if latencies else None,
                rss_start_kb=grew_most["rss_start_kb"], rss_end_kb=grew_most["rss_end_kb"])


def run_e2e(args):
    rounds = {system: [] for system in args.systems}
    for round_index in range(args.rounds):
        order = args.systems if round_index % 2 == 0 else list(reversed(args.systems))
        for system in order:
            rounds[system].append(run_system(args, system, round_index))
    results = [combine_rounds(system, rounds[system]) for system in args.systems]
    for row in results:
        print("%s: CPU %.2f %% (rounds: %s), latency p99 %s ms" % (
            row["system"], row["cpu_percent"], ", ".join("%.2f" % c for c in row["cpu_percent_rounds"]),
            row["latency_p99_ms"]), flush=True)
    return {"duration_s": args.duration_s, "rounds": args.rounds, "rate_hz": args.rate_hz, "battery_rate_hz": 1.0,
            "channels": RC_OUT_CHANNELS, "systems": results}


def annotated_counts(annotate_output):
    """From callgrind_annotate --inclusive=yes --tree=caller: {function: inclusive instructions} and
    {(caller, function): calls}, functions named without their arguments."""
    counts, calls, callers = {}, {}, []
    for line in annotate_output.splitlines():
        # "  1,234 (12.34%)  < file:caller(arguments) (300x) [object]" for each caller, then
        # "  5,678 (56.78%)  *  file:function(arguments) [object]"; the file is ??? without debug info.
        match = re.match(r"\s*([\d,]+)\s+\([\s\d.]+%\)\s+([<*])\s+[^:\s]*:(.+)$", line)
        if not match:
            callers = []
            continue
        name = re.sub(r"\(.*$", "", match.group(3)).strip()
        if match.group(2) == "<":
            count = re.search(r"\(([\d,]+)x\)", match.group(3))
            callers.append((name, int(count.group(1).replace(",", "")) if count else 0))
            continue
        counts[name] = counts.get(name, 0) + int(match.group(1).replace(",", ""))
        for caller, count in callers:
            calls[(caller, name)] = calls.get((caller, name), 0) + count
        callers = []
    return counts, calls


def run_callgrind(args, esc_rate_hz=0.0):
    """Instructions per RCOut message; with esc_rate_hz, ESCTelemetry comes in at that rate too and
    its callback's instructions per message are counted apart."""
    messages = args.callgrind_messages
    rate_hz = 100.0
    name = "callgrind_esc" if esc_rate_hz else "callgrind"
    print("== callgrind: estimator_node, %d RCOut at %g Hz%s" % (
        messages, rate_hz, ", ESCTelemetry at %g Hz" % esc_rate_hz if esc_rate_hz else ""), flush=True)
    out_file = os.path.join(args.work, name + ".out")
    with Master(args.work, name) as master:
        command = ["valgrind", "--tool=callgrind", "--collect-atstart=no",
                   "--toggle-collect=%s*" % CALLGRIND_TOTAL, "--toggle-collect=%s*" % CALLGRIND_ESC,
                   "--callgrind-out-file=" + out_file] + system_command("node", args, master)
        log = open(os.path.join(args.work, name + "_node.log"), "w")
        process = subprocess.Popen(command, env=master.env, stdout=log, stderr=subprocess.STDOUT,
                                   start_new_session=True)
        def zero_after_warmup():
            # Until the hover detector's and the payload's windows are full a message costs less: the
            # counters restart once they are, and the messages counted are the calls of decode.
            time.sleep(CALLGRIND_WARMUP_S)
            subprocess.run(["callgrind_control", "--zero", str(process.pid)], check=True, stdout=subprocess.DEVNULL)

        try:
            probe = run_probe(args, master, name, rate_hz, CALLGRIND_WARMUP_S + messages / rate_hz,
                              ESTIMATE_TOPICS["node"], process, 0, drain_s=30.0, on_load=zero_after_warmup,
                              esc_rate_hz=esc_rate_hz)
            # The counts since the warm-up, dumped while the node runs (into out_file.1): under
            # callgrind the node's shutdown can stall on the master for minutes, and a node killed
            # then writes nothing.
            subprocess.run(["callgrind_control", "--dump", str(process.pid)], check=True, stdout=subprocess.DEVNULL)
        finally:
            stop_group(process, signal.SIGINT, 120.0)
            log.close()
    dump = out_file + ".1"
    if not os.path.exists(dump):
        sys.exit("bench_node.py: callgrind_control --dump wrote no %s" % dump)
    annotate = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--tree=caller", "--threshold=100", dump],
                              capture_output=True, text=True, check=True).stdout
    with open(os.path.join(args.work, name + "_annotate.txt"), "w") as f:
        f.write(annotate)
    counts, calls = annotated_counts(annotate)
    decode = CALLGRIND_PARTS[0][1]
    handled = calls.get((CALLGRIND_TOTAL, decode), 0)
    if not handled:
        sys.exit("bench_node.py: estimator_node under callgrind decoded no RCOut message after the warm-up (%s)"
                 % f.name)
    parts = {}
    for part, name in CALLGRIND_PARTS + [("total", CALLGRIND_TOTAL)]:
        if name not in counts:
            sys.exit("bench_node.py: %s not in callgrind_annotate's output (%s)" % (name, f.name))
        parts[part] = counts[name] / handled
    print("   %d messages decoded after the warm-up: %s instructions per message" % (
        handled, ", ".join("%s %.0f" % item for item in parts.items())), flush=True)
    result = {"rc_out_sent": probe["rc_out_sent"], "handled": handled, "rate_hz": rate_hz,
              "warmup_s": CALLGRIND_WARMUP_S, "published": calls.get((CALLGRIND_TOTAL, CALLGRIND_PARTS[2][1]), 0),
              "measured_s": messages / rate_hz, "instructions_per_message": parts, "command": " ".join(command)}
    if esc_rate_hz:
        esc_handled = calls.get((CALLGRIND_ESC, CALLGRIND_ESC_DECODE), 0)
        if not esc_handled or CALLGRIND_ESC not in counts:
            sys.exit("bench_node.py: estimator_node under callgrind decoded no ESCTelemetry after the warm-up (%s)"
                     % f.name)
        result.update(esc_rate_hz=esc_rate_hz, escs=RC_OUT_CHANNELS, esc_sent=probe["esc_sent"], esc_handled=esc_handled,
                      esc_instructions_per_message=counts[CALLGRIND_ESC] / esc_handled)
        print("   %d ESCTelemetry decoded after the warm-up: %.0f instructions per message" % (
            esc_handled, result["esc_instructions_per_message"]), flush=True)
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", required=True, help="the devel space's executables (bench_probe, estimator_node)")
    parser.add_argument("--repo", required=True)
    parser.add_argument("--work", required=True, help="logs and intermediate files")
    parser.add_argument("--duration-s", type=float, default=60.0, help="load per system and round (e2e)")
    parser.add_argument("--rate-hz", type=float, default=400.0, help="RCOut rate (e2e)")
    parser.add_argument("--rounds", type=int, default=2, help="times each system is loaded (e2e)")
    parser.add_argument("--systems", nargs="+", choices=SYSTEMS, default=list(SYSTEMS),
                        help="the systems under test (e2e), in this order")
    parser.add_argument("--callgrind-messages", type=int, default=2000)
    parser.add_argument("--e2e-json", help="runs the end-to-end part into this file")
    parser.add_argument("--callgrind-json", help="runs the callgrind part into this file")
    args = parser.parse_args()
    if args.rounds < 1:
        parser.error("--rounds: at least 1, not %d" % args.rounds)
    args.bin, args.repo = os.path.abspath(args.bin), os.path.abspath(args.repo)
    os.makedirs(args.work, exist_ok=True)
    if args.e2e_json:
        with open(args.e2e_json, "w") as f:
            json.dump(run_e2e(args), f, indent=1)
    if args.callgrind_json:
        with open(args.callgrind_json, "w") as f:
            result = run_callgrind(args)
            result["with_esc_telemetry"] = run_callgrind(args, CALLGRIND_ESC_RATE_HZ)
            json.dump(result, f, indent=1)


if __name__ == "__main__":
    main()
