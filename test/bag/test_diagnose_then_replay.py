#!/usr/bin/env python3
"""End to end: the correction diagnose_gap finds reaches the vehicle. The simulator flies weighed
flights with an effect the response surfaces leave out (physics: test/bag/diagnose_injected.yaml);
diagnose_gap, told nothing of it, writes report.yaml and corrected_model.yaml; a further flight that
took no part in the diagnosis plays once, on simulated time, through two estimator_nodes, one with
the plain model and one with the corrected_model.yaml as diagnose_gap wrote it. The corrected
node's payload error must fall below the plain node's by the margin the report predicts (its
held-out payload error before minus after), within tolerances that are test parameters."""
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import roslib.packages
import rospy
import rostest
import yaml
from diagnostic_msgs.msg import DiagnosticStatus

from replay_harness import replay

ESTIMATORS = ("plain_estimator", "corrected_estimator")


def flight_profile(template_path, payloads_kg, height_m, out_path):
    """The template profile with this flight's two payloads and hover height; its URDF made absolute."""
    with open(template_path) as f:
        profile = yaml.safe_load(f)
    urdf = profile["vehicle"]["urdf"]
    profile["vehicle"]["urdf"] = os.path.normpath(os.path.join(os.path.dirname(template_path), urdf))
    payloads = [s for s in profile["segments"] if s["type"] == "payload"]
    assert len(payloads) == len(payloads_kg), "the template has %d payload segments" % len(payloads)
    for segment, mass in zip(payloads, payloads_kg):
        segment["mass_kg"] = float(mass)
    for segment in profile["segments"]:
        if segment["type"] == "takeoff":
            segment["height_m"] = float(height_m)
    with open(out_path, "w") as f:
        yaml.safe_dump(profile, f)


def simulate_flight(work, name, flight):
    """Simulates one flight of the test's parameters into WORK/NAME.bag; returns (bag, manifest)."""
    profile = os.path.join(work, name + ".profile.yaml")
    flight_profile(rospy.get_param("~profile"), flight["payloads_kg"], flight["height_m"], profile)
    bag, manifest = os.path.join(work, name + ".bag"), os.path.join(work, name + ".manifest.yaml")
    simulate = roslib.packages.find_node("propulsion_estimator", "simulate")[0]
    subprocess.run([simulate, "flight", "--params", rospy.get_param("~params"), "--profile", profile, "--effects",
                    rospy.get_param("~injected_effects"), "--seed", str(flight["seed"]), "--bag", bag,
                    "--manifest", manifest], check=True, stdout=subprocess.DEVNULL)
    return bag, manifest


def relative_payload_error(report):
    """RMS over the payload segments of (estimate - weighed) / weighed, as diagnose_gap reports it."""
    rows = report.rows()[1:]
    return math.sqrt(sum(((r["payload_kg"] - r["true_payload_kg"]) / r["true_payload_kg"]) ** 2 for r in rows)
                     / len(rows))


class DiagnoseThenReplayTest(unittest.TestCase):
    def test_the_written_correction_shrinks_the_payload_error_as_predicted(self):
        rospy.init_node("test_diagnose_then_replay")
        work = tempfile.mkdtemp(prefix="pe_diagnose_replay_")
        self.addCleanup(shutil.rmtree, work, True)

        # The weighed flights diagnose_gap sees, in one manifest.
        flights = []
        for i, flight in enumerate(rospy.get_param("~diagnosis_flights")):
            _, manifest = simulate_flight(work, "diagnosis_%d" % i, flight)
            with open(manifest) as f:
                flights += yaml.safe_load(f)["flights"]
        manifest = os.path.join(work, "diagnosis.manifest.yaml")
        with open(manifest, "w") as f:
            yaml.safe_dump({"flights": flights}, f)
        out = os.path.join(work, "gap")
        diagnose = roslib.packages.find_node("propulsion_estimator", "diagnose_gap")[0]
        model, urdf = rospy.get_param("~model"), rospy.get_param("~urdf")
        run = subprocess.run([diagnose, "--model", model, "--urdf", urdf, "--manifest", manifest, "--out", out,
                              "--python", sys.executable], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             universal_newlines=True)
        print(run.stdout)
        self.assertEqual(run.returncode, 0, "diagnose_gap failed")

        # What the report predicts, from flights held out of each fit.
        with open(os.path.join(out, "report.yaml")) as f:
            report = yaml.safe_load(f)
        heldout = report["heldout"]
        predicted_pct = heldout["before_payload_err_pct"] - heldout["after_payload_err_pct"]
        print("diagnose_gap: selected %s; held-out payload error %.2f %% -> %.2f %% (predicted shrink %.2f points)" %
              (report["selected"], heldout["before_payload_err_pct"], heldout["after_payload_err_pct"], predicted_pct))
        self.assertGreaterEqual(predicted_pct, rospy.get_param("~min_predicted_shrink_pct"),
                                "the report predicts too small a shrink for this test to mean anything")
        corrected_model = os.path.join(out, "corrected_model.yaml")
        with open(corrected_model) as f:
            effects = yaml.safe_load(f).get("effects")
        self.assertTrue(effects, "corrected_model.yaml has no effects: section")

        # A flight that took no part in the diagnosis, through the plain and the corrected model.
        bag, heldout_manifest = simulate_flight(work, "replayed", rospy.get_param("~replayed_flight"))
        reports, effects_status, player_status = replay(
            bag, heldout_manifest, {ESTIMATORS[0]: model, ESTIMATORS[1]: corrected_model}, urdf,
            rospy.get_param("~rate"))
        self.assertEqual(player_status, 0)
        errors_pct = {}
        for name in ESTIMATORS:
            segments = reports[name]
            self.assertTrue(segments.tared, "%s: no successful ~tare in the empty segment: %s" %
                            (name, segments.tare_answer))
            print("%s (%s):\n%s" % (name, segments.tare_answer, segments.table()))
            for row in segments.rows():
                self.assertEqual(row["state"], "hovering", "%s: segment %d never hovering" % (name, row["segment"]))
            errors_pct[name] = 100.0 * relative_payload_error(segments)
        shrink_pct = errors_pct["plain_estimator"] - errors_pct["corrected_estimator"]
        print("replayed flight, payload error: plain model %.2f %%, corrected model %.2f %% (shrink %.2f points; "
              "predicted %.2f)" % (errors_pct["plain_estimator"], errors_pct["corrected_estimator"], shrink_pct,
                                   predicted_pct))

        # The node shrinks the error by the predicted margin, up to the tolerances.
        self.assertGreaterEqual(shrink_pct, rospy.get_param("~shrink_fraction_of_predicted") * predicted_pct)
        self.assertLessEqual(errors_pct["corrected_estimator"],
                             heldout["after_payload_err_pct"] + rospy.get_param("~corrected_error_tolerance_pct"))
        # The node applied what the report selected, read from the file diagnose_gap wrote.
        corrected = effects_status.get("corrected_estimator")
        self.assertIsNotNone(corrected, "no Effects diagnostic from the corrected estimator")
        self.assertEqual(corrected.level, DiagnosticStatus.OK, corrected.message)
        self.assertTrue(corrected.message.startswith("applied: "), corrected.message)
        self.assertEqual(set(corrected.message[len("applied: "):].split(", ")), set(effects))


if __name__ == "__main__":
    rostest.rosrun("propulsion_estimator", "diagnose_then_replay", DiagnoseThenReplayTest)
