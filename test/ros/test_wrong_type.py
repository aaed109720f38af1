#!/usr/bin/env python3
"""rostest: a message of another type on the RCOut topic is refused with a clear error."""
import unittest

import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from propulsion_estimator.msg import MotorEstimates
from sensor_msgs.msg import BatteryState
from std_msgs.msg import Float64

EXPECTED = ("/mavros/rc/out: expected mavros_msgs/RCOut (md5sum 52cacf104bab5ae3b103cfe176590713), "
            "got std_msgs/Float64 (md5sum fdb28210bfa9d7c91146260178d9a584)")


class WrongTypeTest(unittest.TestCase):
    def test_refuses_other_types(self):
        rospy.init_node("test_wrong_type")
        statuses, estimates = [], []
        rospy.Subscriber("/diagnostics", DiagnosticArray,
                         lambda m: statuses.extend(s for s in m.status if s.name.endswith("Motor outputs")))
        rospy.Subscriber("/propulsion_estimator/motors", MotorEstimates, estimates.append)
        battery = rospy.Publisher("/mavros/battery", BatteryState, queue_size=1)
        wrong = rospy.Publisher("/mavros/rc/out", Float64, queue_size=10)
        end = rospy.Time.now() + rospy.Duration(20.0)
        while not any(s.message == EXPECTED for s in statuses):
            self.assertLess(rospy.Time.now(), end, "no diagnostic; last: %s" % (statuses[-1:] or "none"))
            battery.publish(BatteryState(voltage=11.4))
            wrong.publish(Float64(1690.0))
            rospy.sleep(0.1)
        self.assertEqual([s.level for s in statuses if s.message == EXPECTED][0], DiagnosticStatus.ERROR)
        self.assertEqual(estimates, [])


if __name__ == "__main__":
    rostest.rosrun("propulsion_estimator", "wrong_type", WrongTypeTest)
