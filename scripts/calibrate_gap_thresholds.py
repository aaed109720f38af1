#!/usr/bin/env python3
"""Calibrates diagnose_gap's thresholds of improvement on null flights of the randomized family.

Reads the reports validate_gap.py wrote in --work for cases with nothing to name (null,
centre-of-gravity and weak-propeller cases: only the mismatch of model family between the
simulator and the fitted surfaces, plus a motor fault the moment balance takes) and prints, over
every first-round candidate whose improvement is significant, the largest fall of the PWM view's
held-out RMSE (percentage points of the truth) and of its mean square (fraction), and of the RPM
view's where the flights had ESC telemetry (the same thresholds apply to it): what a mismatch
of model family alone gives. An effect must do better to be named; the chosen values go into
DiagnosisConfig (include/propulsion_estimator/gap/diagnosis.h) and docs/VALIDATION.md says which seeds.
For each effect whose law acts on some blocks only (ground effect, climb inflow, translational
lift) it prints the same on those blocks (the trace's regional_* fields), in either view, and a
threshold 25 % above the largest (min_regional_improvement_pct: the code judges the ground effect
there; the others' floor is so high that a fall beyond it clears the threshold over all blocks too);
and, for such an effect judged after an earlier one (a later round, or beside a suspect motor's
factor), the largest such fall over every case where that effect was not injected: what an
earlier law's leftover gives there, and a threshold 25 % above it
(min_later_regional_improvement_pct: law_left_over.cpp).
Run it on development seeds only.

Usage: calibrate_gap_thresholds.py WORK_DIR [WORK_DIR ...] [--significance P]
"""
import argparse
import glob
import os

import yaml

NOTHING_TO_NAME = ("null", "cg_offset", "weak_propeller")
# The family flies every flight with weak ground effect, climb inflow and translational lift
# (validate_gap.BACKGROUND_STRENGTH, at most 0.25); a case's own draw of one is 0.7 or more.
BACKGROUND_AT_MOST = 0.25


def injected(case_folder, name):
    """Whether the case's flights carry `name` beyond the family's background (its effects file)."""
    path = os.path.join(case_folder, "flight_1.effects.yaml")
    if not os.path.exists(path):
        return os.path.basename(case_folder).endswith(name)
    with open(path) as handle:
        params = (yaml.safe_load(handle) or {}).get(name)
    if params is None:
        return False
    return params.get("strength", BACKGROUND_AT_MOST + 1.0) > BACKGROUND_AT_MOST


def regional_fall(step):
    """The larger fall of the two views on the blocks where the step's effect acts; None without."""
    falls = [step["base_regional_%srmse_pct" % view] - step["regional_%srmse_pct" % view]
             for view in ("", "rpm_") if step.get("regional_%srmse_pct" % view) is not None]
    return max(falls) if falls else None


def later_regional_floors(works, significance):
    """Per effect read where its law acts: the largest significant fall there when judged after an
    earlier effect or a suspect's factor, over the cases where it was not injected."""
    floors = {}
    for work in works:
        for report_path in sorted(glob.glob(os.path.join(work, "case_*", "diagnosis", "report.yaml"))):
            folder = os.path.dirname(os.path.dirname(report_path))
            with open(report_path) as handle:
                report = yaml.safe_load(handle)
            for step in report.get("trace") or []:
                fall = regional_fall(step)
                later = step["round"] > 1 or report.get("suspect_motor") is not None
                if fall is None or not later or step["p_value"] >= significance or injected(folder, step["name"]):
                    continue
                floors.setdefault(step["name"], []).append((fall, os.path.basename(work), os.path.basename(folder)))
    return floors


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("work", nargs="+")
    parser.add_argument("--significance", type=float, default=0.01)
    args = parser.parse_args()
    rows, rpm_rows = [], []
    regional = {}
    for work in args.work:
        for report_path in sorted(glob.glob(os.path.join(work, "case_*", "diagnosis", "report.yaml"))):
            case = os.path.basename(os.path.dirname(os.path.dirname(report_path)))
            if not case.endswith(NOTHING_TO_NAME):
                continue
            with open(report_path) as handle:
                report = yaml.safe_load(handle)
            for step in report.get("trace") or []:
                if step["round"] != 1 or step["p_value"] >= args.significance:
                    continue
                # The error the candidate was compared against: on the blocks the selection ran on
                # (the steady ones alone when transient ones are in), not the report's over all.
                before = step.get("base_heldout_rmse_pct", report["heldout"]["before_rmse_pct"])
                drop = before - step["heldout_rmse_pct"]
                ratio = (step["heldout_rmse_pct"] / before) ** 2 if before else 1.0
                rows.append((drop, ratio, os.path.basename(work), case, step["name"]))
                # Where its law acts, in either view: its own floor.
                for view in ("", "rpm_"):
                    if step.get("regional_%srmse_pct" % view) is not None:
                        fall = step["base_regional_%srmse_pct" % view] - step["regional_%srmse_pct" % view]
                        regional.setdefault(step["name"], []).append(
                            (fall, view or "pwm_", os.path.basename(work), case))
                # The RPM view's fall, where the flights had one: its test uses the same thresholds.
                if step.get("rpm_rmse_pct") is not None and step.get("base_rpm_rmse_pct"):
                    before = step["base_rpm_rmse_pct"]
                    rpm_rows.append((before - step["rpm_rmse_pct"], (step["rpm_rmse_pct"] / before) ** 2,
                                     os.path.basename(work), case, step["name"]))
    rows.sort(reverse=True)
    print("%d significant first-round candidates on null flights" % len(rows))
    for drop, ratio, work, case, name in rows[:15]:
        print("  %-14s %-28s %-18s RMSE falls %.3f points, mean square to %.3f" % (work, case, name, drop, ratio))
    if rows:
        print("largest fall: %.3f points; lowest mean-square ratio: %.3f" % (rows[0][0], min(r[1] for r in rows)))
    rpm_rows.sort(reverse=True)
    print("RPM view: %d of them with ESC telemetry" % len(rpm_rows))
    for drop, ratio, work, case, name in rpm_rows[:5]:
        print("  %-14s %-28s %-18s RMSE falls %.3f points, mean square to %.3f" % (work, case, name, drop, ratio))

    for name, falls in sorted(regional.items()):
        falls.sort(reverse=True)
        fall, view, work, case = falls[0]
        print("where %s acts: %d falls; largest %.3f points (%s view, %s %s): threshold %.3f" %
              (name, len(falls), fall, view[:-1], work, case, 1.25 * fall))
    for name, falls in sorted(later_regional_floors(args.work, args.significance).items()):
        falls.sort(reverse=True)
        fall, work, case = falls[0]
        print("where %s acts, after an earlier effect where none was injected: %d falls; largest %.3f points "
              "(%s %s): threshold %.3f" % (name, len(falls), fall, work, case, 1.25 * fall))


if __name__ == "__main__":
    main()
