#!/usr/bin/env python3
"""make bench-arm64: writes docs/BENCHMARKS.arm64.md, the fragment `make bench` pastes into docs/BENCHMARKS.md
under "arm64, emulated", from the google-benchmark JSON of bench_estimator cross-built for arm64
and run under qemu-user.

Usage: scripts/write_arm64_benchmarks.py --json FILE --out FILE --command TEXT"""
import argparse
import datetime
import json
import subprocess

from write_benchmarks import UNIT_SECONDS, format_seconds


def first_line(command):
    try:
        return subprocess.run(command, capture_output=True, text=True, check=False).stdout.splitlines()[0]
    except (OSError, IndexError):
        return "unknown"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--json", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--command", required=True)
    args = parser.parse_args()
    with open(args.json) as f:
        results = json.load(f)
    with open("/proc/loadavg") as f:
        load = " ".join(f.read().split()[:3])
    lines = [
        "The core per-message figures for the Raspberry Pi's architecture, **emulated, not measured on a",
        "Pi**: `bench_estimator` (ROS-free; `BM_RcOutDecode` needs ROS and is not cross-built) cross-compiled",
        "for arm64 (%s, Release `-O3`, generic armv8-a) and run under user-mode emulation (%s) on this"
        % (first_line(["aarch64-linux-gnu-g++", "--version"]), first_line(["qemu-aarch64", "--version"])),
        "machine, %s, load average %s at the end. Emulation costs about ten times the native CPU time,"
        % (datetime.datetime.utcnow().strftime("%Y-%m-%d"), load),
        "so these figures say nothing of a Pi's speed; they show that the pipeline runs on arm64 and",
        "bound its cost under emulation.",
        "",
        "| benchmark | CPU time (emulated) | wall time |",
        "|---|---:|---:|",
    ]
    for row in results["benchmarks"]:
        scale = UNIT_SECONDS[row["time_unit"]]
        lines.append("| `%s` | %s | %s |" % (row["name"], format_seconds(row["cpu_time"] * scale),
                                             format_seconds(row["real_time"] * scale)))
    lines += ["", "Command: `%s`." % args.command]
    with open(args.out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
