#!/usr/bin/env python3
"""Bag replay test of the effects: the simulator flies a profile with effects the response surfaces
leave out (physics, independent of the surfaces), and the bag plays once on simulated time through
two estimator_nodes, one with the plain model and one with the model plus an effects: section
written here. The corrected model's payload error must be below the plain model's, by a margin,
and within a tolerance; tolerances are test parameters."""
import os
import shutil
import subprocess
import tempfile
import unittest

import roslib.packages
import rospy
import rostest
import yaml
from diagnostic_msgs.msg import DiagnosticStatus

from replay_harness import replay

ESTIMATORS = ("plain_estimator", "corrected_estimator")


class ReplayEffectsTest(unittest.TestCase):
    def test_the_corrected_model_estimates_the_payload_better(self):
        rospy.init_node("test_replay_effects")
        work = tempfile.mkdtemp(prefix="pe_effects_")
        self.addCleanup(shutil.rmtree, work, True)
        bag_path, manifest = os.path.join(work, "flight.bag"), os.path.join(work, "flight.manifest.yaml")
        simulate = roslib.packages.find_node("propulsion_estimator", "simulate")[0]
        subprocess.run([simulate, "flight", "--params", rospy.get_param("~params"), "--profile",
                        rospy.get_param("~profile"), "--effects", rospy.get_param("~injected_effects"), "--seed",
                        str(rospy.get_param("~seed")), "--bag", bag_path, "--manifest", manifest],
                       check=True, stdout=subprocess.DEVNULL)

        # The corrected model: the plain model's file plus an effects: section.
        plain_model = rospy.get_param("~model")
        corrected_model = os.path.join(work, "corrected_model.yaml")
        with open(plain_model) as f:
            text = f.read()
        with open(corrected_model, "w") as f:
            f.write(text + "\n" + yaml.safe_dump({"effects": rospy.get_param("~model_effects")},
                                                 default_flow_style=None))

        reports, effects_status, player_status = replay(
            bag_path, manifest, {ESTIMATORS[0]: plain_model, ESTIMATORS[1]: corrected_model},
            rospy.get_param("~urdf"), rospy.get_param("~rate"))
        self.assertEqual(player_status, 0)

        errors = {}
        for name in ESTIMATORS:
            report = reports[name]
            self.assertTrue(report.tared, "%s: no successful ~tare in the empty segment: %s" % (name, report.tare_answer))
            print("%s (%s):\n%s" % (name, report.tare_answer, report.table()))
            rows = report.rows()
            for row in rows:
                self.assertEqual(row["state"], "hovering", "%s: segment %d never hovering" % (name, row["segment"]))
                self.assertGreater(row["samples"], 100, "%s: segment %d" % (name, row["segment"]))
            errors[name] = max(abs(row["payload_kg"] - row["true_payload_kg"]) for row in rows[1:])
        print("payload error: plain model %.4f kg, corrected model %.4f kg" %
              (errors["plain_estimator"], errors["corrected_estimator"]))

        self.assertLessEqual(errors["corrected_estimator"], rospy.get_param("~payload_tolerance_kg"))
        self.assertGreaterEqual(errors["plain_estimator"] - errors["corrected_estimator"],
                                rospy.get_param("~min_improvement_kg"))
        total_tolerance = rospy.get_param("~total_tolerance_fraction")
        for row in reports["corrected_estimator"].rows():
            self.assertAlmostEqual(row["total_kg"], row["true_total_kg"], delta=total_tolerance * row["true_total_kg"],
                                   msg="corrected model, segment %d total mass" % row["segment"])

        # The corrected node applied both corrections; the plain one had none to apply.
        corrected = effects_status.get("corrected_estimator")
        self.assertIsNotNone(corrected, "no Effects diagnostic from the corrected estimator")
        self.assertEqual(corrected.level, DiagnosticStatus.OK, corrected.message)
        self.assertEqual(corrected.message, "applied: supply_resistance, thrust_loss")
        self.assertEqual(effects_status["plain_estimator"].message, "none: the model has no effects")


if __name__ == "__main__":
    rostest.rosrun("propulsion_estimator", "replay_effects", ReplayEffectsTest)
