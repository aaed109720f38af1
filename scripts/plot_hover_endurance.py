#!/usr/bin/env python3
"""Draws the hover time left over a flight with its 90 % interval against the truth, from the CSV
that CapabilityFlight.TheHoverTimeLeftOverAFlightWithItsInterval writes (PE_ENDURANCE_CSV):

    PE_ENDURANCE_CSV=/tmp/endurance.csv .ws/ros_free/test_onboard \
        --gtest_filter='CapabilityFlight.TheHoverTimeLeftOverAFlightWithItsInterval'
    scripts/plot_hover_endurance.py /tmp/endurance.csv docs/images/hover_time_left_interval.png

The test computes every number; this script only draws. Needs Debian's python3-matplotlib.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(argv):
    if len(argv) != 3:
        sys.stderr.write("usage: plot_hover_endurance.py CSV PNG\n")
        return 2
    with open(argv[1], newline="") as f:
        rows = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]
    if not rows:
        sys.stderr.write("plot_hover_endurance.py: %s: no rows\n" % argv[1])
        return 1
    t = [r["after_takeoff_s"] for r in rows]
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    ax.fill_between(t, [r["low_s"] for r in rows], [r["high_s"] for r in rows], color="tab:blue", alpha=0.2,
                    label="90 % interval")
    ax.plot(t, [r["predicted_s"] for r in rows], color="tab:blue", label="hover time left (predicted)")
    ax.plot(t, [r["flown_s"] for r in rows], color="black", linestyle="--", label="hover time left (truth)")
    ax.set_xlabel("time since take-off (s)")
    ax.set_ylabel("hover time left to the loaded cut-off (s)")
    ax.set_title("Hover time left on a pack's first flight, from 100 % (battery family pack 406777)")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(argv[2], dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
