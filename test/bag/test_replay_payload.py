#!/usr/bin/env python3
"""Bag replay test: the simulator flies a profile into a bag at test time (physics, independent of
the response surfaces), the bag plays on simulated time through the running estimator_node, and
the estimates are checked against the manifest's true masses and the bag's /sim/truth, with
tolerances given as test parameters. Then `estimate` runs on the same bag and on the same flight
logged as a PX4 ULog and an ArduPilot DataFlash log: every hover's mass as the node said it."""
import csv
import os
import shutil
import subprocess
import tempfile
import unittest

import rosbag
import roslib.packages
import rospy
import rostest
from propulsion_estimator.msg import PayloadEstimate, PropulsionTotals, SimTruth
from std_srvs.srv import Trigger

from replay_harness import SegmentReport, load_segments, play


class ReplayPayloadTest(unittest.TestCase):
    def test_payload_of_a_simulated_flight(self):
        rospy.init_node("test_replay_payload")
        work = tempfile.mkdtemp(prefix="pe_replay_")
        self.addCleanup(shutil.rmtree, work, True)
        bag_path, manifest = os.path.join(work, "flight.bag"), os.path.join(work, "flight.manifest.yaml")
        simulate = roslib.packages.find_node("propulsion_estimator", "simulate")[0]
        command = [simulate, "flight", "--params", rospy.get_param("~params"), "--profile", rospy.get_param("~profile"),
                   "--seed", str(rospy.get_param("~seed")), "--bag", bag_path, "--manifest", manifest]
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
        _, segments = load_segments(manifest)
        with rosbag.Bag(bag_path) as bag:
            start = bag.get_start_time()
        report = SegmentReport(segments, start, tare_segment=0)

        # Hover-averaged estimated thrust against the simulator's true thrust, per segment.
        truth_sum, estimate_sum = [0.0] * len(segments), [0.0] * len(segments)

        def in_segment(stamp):
            for i, s in enumerate(segments):
                if start + s["start"] <= stamp <= start + s["end"]:
                    return i
            return None

        def on_truth(message):
            i = in_segment(message.header.stamp.to_sec())
            if i is not None:
                truth_sum[i] += sum(m.thrust_n for m in message.motors)

        def on_totals(message):
            i = in_segment(message.header.stamp.to_sec())
            if i is not None:
                estimate_sum[i] += message.thrust_n

        rospy.Subscriber("/propulsion_estimator/payload", PayloadEstimate, report.on_payload)
        rospy.Subscriber("/propulsion_estimator/totals", PropulsionTotals, on_totals)
        rospy.Subscriber("/sim/truth", SimTruth, on_truth)
        rospy.wait_for_service("/propulsion_estimator/tare", timeout=30.0)
        tare = rospy.ServiceProxy("/propulsion_estimator/tare", Trigger)

        self.assertEqual(play(bag_path, rospy.get_param("~rate"), [(report, tare)]), 0)
        self.assertTrue(report.tared, "no successful ~tare in the empty segment: %s" % report.tare_answer)
        print(report.table())

        payload_tolerance = rospy.get_param("~payload_tolerance_kg")
        total_tolerance = rospy.get_param("~total_tolerance_fraction")
        thrust_tolerance = rospy.get_param("~thrust_tolerance_fraction")
        for row in report.rows():
            i = row["segment"]
            self.assertEqual(row["state"], "hovering", "segment %d never hovering" % i)
            self.assertGreater(row["samples"], 100, "segment %d" % i)
            self.assertAlmostEqual(row["payload_kg"], row["true_payload_kg"], delta=payload_tolerance,
                                   msg="segment %d payload" % i)
            self.assertAlmostEqual(row["total_kg"], row["true_total_kg"], delta=total_tolerance * row["true_total_kg"],
                                   msg="segment %d total mass" % i)
            self.assertGreater(truth_sum[i], 0.0)
            self.assertAlmostEqual(estimate_sum[i] / truth_sum[i], 1.0, delta=thrust_tolerance,
                                   msg="segment %d: estimated over true thrust" % i)

        # estimate, offline, on the bag the node heard and on the same flight in the autopilots' logs.
        logs = {"bag": bag_path}
        for log_format, extension in (("ulog", "ulg"), ("dataflash", "bin")):
            logs[log_format] = os.path.join(work, "flight." + extension)
            subprocess.run(command[:command.index("--bag")] + ["--log", logs[log_format], "--log-format", log_format],
                           check=True, stdout=subprocess.DEVNULL)
        estimate = roslib.packages.find_node("propulsion_estimator", "estimate")[0]
        package = roslib.packages.get_pkg_dir("propulsion_estimator")
        for log_format, log in logs.items():
            out = os.path.join(work, "estimate_" + log_format)
            subprocess.run([estimate, "--model", os.path.join(package, "config/e300_dji2212_dji9443.yaml"),
                            "--urdf", os.path.join(package, "config/f450_quad.urdf"), "--sample-rate-hz", "0",
                            "--no-figures", "--out", out, log], check=True, stdout=subprocess.DEVNULL)
            name = os.path.splitext(os.path.basename(log))[0]
            with open(os.path.join(out, name, "estimates.csv"), newline="") as handle:
                rows = list(csv.DictReader(handle))
            # The node publishes at most 50 Hz: its last hover message in a segment may be a few
            # messages before the offline estimate's, and the autopilots' logs hold floats.
            tolerance = 0.002 if log_format == "bag" else 0.005
            for row in report.rows():
                segment = segments[row["segment"]]
                offline = [float(r["total_mass_kg"]) for r in rows
                           if r["hovering"] == "1" and segment["start"] <= float(r["time_s"]) <= segment["end"]]
                print("%s, segment %d: the node %.4f kg, estimate %s" % (log_format, row["segment"], row["total_kg"],
                                                                   "%.4f kg" % offline[-1] if offline else "no hover"))
                self.assertTrue(offline, "%s: estimate found no hover in segment %d" % (log_format, row["segment"]))
                self.assertAlmostEqual(offline[-1], row["total_kg"], delta=tolerance * row["total_kg"],
                                       msg="%s: segment %d, estimate against the node" % (log_format, row["segment"]))


if __name__ == "__main__":
    rostest.rosrun("propulsion_estimator", "replay_payload", ReplayPayloadTest)
