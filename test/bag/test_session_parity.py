#!/usr/bin/env python3
"""The node and the offline replay drive one onboard session (issue 34): a flight simulated at test
time is played through estimator_node and given to `estimate`; the node's last ~capability and
estimate's summary must give the same motor-health verdict (flagged channel, each motor's thrust
gap) and the same live ESC check verdict on the same channel, and that verdict must name the
simulated fault (so that agreeing on nothing cannot pass)."""
import os
import re
import shutil
import subprocess
import tempfile
import time
import unittest

import roslib.packages
import rospy
import rostest
from propulsion_estimator.msg import Capability

from replay_harness import play


def estimate_summary(log, model, urdf, out):
    estimate = roslib.packages.find_node("propulsion_estimator", "estimate")[0]
    subprocess.run([estimate, "--model", model, "--urdf", urdf, "--no-figures", "--out", out, log], check=True,
                   stdout=subprocess.DEVNULL)
    name = os.path.splitext(os.path.basename(log))[0]
    with open(os.path.join(out, name, "summary.md")) as handle:
        return handle.read()


def motor_health_of(summary):
    """(flagged channel or 0, {channel: thrust gap in %}) from the summary's Motor health section."""
    section = summary.split("## Motor health")[1].split("## ")[0]
    stands_out = re.search(r"channel (\d+) stands out", section)
    gaps = {int(m.group(1)): float(m.group(2)) for m in re.finditer(r"^\| (\d+) \| (-?[\d.]+) % \|", section, re.M)}
    return (int(stands_out.group(1)) if stands_out else 0), gaps


def esc_check_of(summary):
    """(verdict, flagged channel or 0) of the summary's last ESC judgement."""
    match = re.search(r"Last judgement: \*\*(\w+)\*\*(?: on channel (\d+))?", summary)
    if not match:
        return "not_judged", 0
    return match.group(1), int(match.group(2) or 0)


class SessionParityTest(unittest.TestCase):
    def test_the_node_and_estimate_give_the_same_verdicts(self):
        rospy.init_node("test_session_parity")
        work = tempfile.mkdtemp(prefix="pe_parity_")
        self.addCleanup(shutil.rmtree, work, True)
        bag = os.path.join(work, "flight.bag")
        simulate = roslib.packages.find_node("propulsion_estimator", "simulate")[0]
        subprocess.run([simulate, "flight", "--params", rospy.get_param("~params"), "--profile",
                        rospy.get_param("~profile"), "--seed", str(rospy.get_param("~seed")), "--bag", bag],
                       check=True, stdout=subprocess.DEVNULL)

        node = {}

        def on_capability(message):
            node["last"] = message
            if message.model_check_verdict not in ("not_judged", ""):
                node["judged"] = message

        rospy.Subscriber("/propulsion_estimator/capability", Capability, on_capability)
        rospy.wait_for_service("/propulsion_estimator/tare", timeout=30.0)
        self.assertEqual(play(bag, rospy.get_param("~rate"), []), 0)
        time.sleep(2.0)  # wall time: simulated time stops with the bag
        self.assertIn("judged", node, "the node's live ESC check never judged")

        summary = estimate_summary(bag, rospy.get_param("~model"), rospy.get_param("~urdf"), os.path.join(work, "out"))
        offline_flag, offline_gaps = motor_health_of(summary)
        offline_verdict, offline_channel = esc_check_of(summary)
        last, judged = node["last"], node["judged"]
        print("node: motor health flags %d, gaps %s; ESC check %s on %d" % (
            last.flagged_channel, ["%.1f" % (100 * g) for g in last.motor_thrust_gap], judged.model_check_verdict,
            judged.model_check_flagged_channel))
        print("estimate: motor health flags %d, gaps %s; ESC check %s on %d" % (
            offline_flag, offline_gaps, offline_verdict, offline_channel))

        # The fault is named, by both.
        self.assertEqual(offline_verdict, "propeller")
        self.assertEqual(offline_channel, 2)
        self.assertEqual(judged.model_check_verdict, offline_verdict)
        self.assertEqual(judged.model_check_flagged_channel, offline_channel)

        self.assertTrue(last.motor_health_judged, last.motor_health_note)
        self.assertEqual(last.flagged_channel, offline_flag)
        self.assertEqual(sorted(offline_gaps), list(last.motor_channels))
        tolerance = rospy.get_param("~gap_tolerance_pct")
        for channel, gap in zip(last.motor_channels, last.motor_thrust_gap):
            self.assertAlmostEqual(100.0 * gap, offline_gaps[channel], delta=tolerance, msg="channel %d" % channel)


if __name__ == "__main__":
    rostest.rosrun("propulsion_estimator", "session_parity", SessionParityTest)
