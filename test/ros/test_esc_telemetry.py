#!/usr/bin/env python3
"""estimator_node with ESC telemetry (issue 21): mavros_msgs/ESCStatus (PX4) published through a
class genpy builds from the message's definition (Debian has no mavros_msgs), measured rpm and
current on ~motors beside the modelled ones, and the "ESC telemetry" diagnostic while it is
missing, fresh and stale. Estimates never depend on it."""
import math
import sys
import time
import unittest

import genpy.dynamic
import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticStatus
from std_msgs.msg import Header

sys.path.insert(0, __file__.rsplit("/", 1)[0])
from estimator_harness import EstimatorHarness  # noqa: E402

# mavros_msgs/ESCStatus as mavros 1.x and 2.x define it, with its nested types.
ITEM = ("# ESCStatusItem.msg\n#\n#\n# See mavlink message documentation here:\n"
        "# https://mavlink.io/en/messages/common.html#ESC_STATUS\n\n"
        "std_msgs/Header header\n\nint32 rpm\nfloat32 voltage\nfloat32 current\n")
DEFINITION = ("# ESCStatus.msg\n#\n#\n# See mavlink message documentation here:\n"
              "# https://mavlink.io/en/messages/common.html#ESC_STATUS\n\n"
              "std_msgs/Header header\n\nmavros_msgs/ESCStatusItem[] esc_status\n\n" + "=" * 80 +
              "\nMSG: std_msgs/Header\n" + Header._full_text + "\n" + "=" * 80 +
              "\nMSG: mavros_msgs/ESCStatusItem\n" + ITEM)
CLASSES = genpy.dynamic.generate_dynamic("mavros_msgs/ESCStatus", DEFINITION)
ESCStatus, ESCStatusItem = CLASSES["mavros_msgs/ESCStatus"], CLASSES["mavros_msgs/ESCStatusItem"]


class EscTelemetryTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("esc_telemetry_test")
        cls.h = EstimatorHarness()
        cls.esc_pub = rospy.Publisher("/mavros/esc_status", ESCStatus, queue_size=10)
        cls.h.wait_for(lambda: cls.esc_pub.get_num_connections() > 0, 10.0, "the node subscribing to esc_status")

    def status(self):
        self.h.wait_for(lambda: "ESC telemetry" in self.h.diagnostics, 10.0, "the ESC telemetry diagnostic")
        return self.h.diagnostics["ESC telemetry"]

    def fly(self, seconds, telemetry):
        end = time.time() + seconds
        step = 0
        while time.time() < end and not rospy.is_shutdown():
            self.h.rc_out([1690, 1690, 1690, 1690, 0, 0, 0, 0])
            if step % 50 == 0:
                self.h.battery(11.4)
            if telemetry and step % 5 == 0:
                stamp = rospy.Time.now()
                items = [ESCStatusItem(header=Header(stamp=stamp), rpm=7000 + k + step, voltage=11.3, current=5.0 + 0.01 * k)
                         for k in range(4)]
                self.esc_pub.publish(ESCStatus(header=Header(stamp=stamp), esc_status=items))
            step += 1
            time.sleep(0.02)

    def test_missing_fresh_and_stale(self):
        self.assertEqual(ESCStatus._md5sum, "145d49eaf5cfecbdfd50ae4a22fe82d4")
        self.fly(1.5, telemetry=False)
        status = self.status()
        self.assertEqual(status.level, DiagnosticStatus.OK, status.message)
        self.assertTrue(status.message.startswith("no ESC telemetry"), status.message)
        self.assertTrue(math.isnan(self.h.motors[-1].motors[0].measured_rpm))
        modelled = self.h.motors[-1].motors[0].rpm

        self.fly(2.5, telemetry=True)
        motor = self.h.motors[-1].motors[2]
        self.assertGreater(motor.measured_rpm, 7000.0)
        self.assertLess(motor.measured_rpm, 7300.0)
        self.assertAlmostEqual(motor.measured_current_a, 5.02, places=4)
        self.assertAlmostEqual(motor.rpm_ratio, motor.measured_rpm / motor.rpm, places=6)
        self.assertEqual(self.h.motors[-1].motors[0].rpm, modelled)  # the estimate does not change
        self.h.wait_for(lambda: "4 of 4" in dict((v.key, v.value) for v in self.status().values).get("fresh_motors", ""),
                        5.0, "every motor fresh on the diagnostic")

        self.fly(2.0, telemetry=False)
        self.assertTrue(math.isnan(self.h.motors[-1].motors[2].measured_rpm))
        self.h.wait_for(lambda: self.status().message.startswith("ESC telemetry stale on 4 of 4 motors"), 5.0,
                        "the stale telemetry on the diagnostic")
        self.assertEqual(self.status().level, DiagnosticStatus.WARN)
        self.assertEqual(self.h.capability[-1].model_check_verdict, "not_judged")


if __name__ == "__main__":
    rostest.rosrun("propulsion_estimator", "esc_telemetry", EscTelemetryTest)
