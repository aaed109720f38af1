"""Black-box access to a running estimator_node for rostests: publish inputs, watch outputs and
/diagnostics, call services."""
import math
import threading
import time

import rospy
from diagnostic_msgs.msg import DiagnosticArray
from propulsion_estimator.msg import Capability, MotorEstimates, PayloadEstimate, PropulsionTotals
from sensor_msgs.msg import BatteryState
from std_srvs.srv import Trigger

from rcout import RCOut


class EstimatorHarness:
    def __init__(self, node="/propulsion_estimator", battery_topic="/mavros/battery", rc_out_topic="/mavros/rc/out"):
        self.node = node
        self._lock = threading.Lock()
        self.motors, self.totals, self.payload, self.capability = [], [], [], []
        self.diagnostics = {}
        self.battery_pub = rospy.Publisher(battery_topic, BatteryState, queue_size=10)
        self.rc_out_pub = rospy.Publisher(rc_out_topic, RCOut, queue_size=100)
        rospy.Subscriber(node + "/motors", MotorEstimates, self._keep, self.motors)
        rospy.Subscriber(node + "/totals", PropulsionTotals, self._keep, self.totals)
        rospy.Subscriber(node + "/payload", PayloadEstimate, self._keep, self.payload)
        rospy.Subscriber(node + "/capability", Capability, self._keep, self.capability)
        rospy.Subscriber("/diagnostics", DiagnosticArray, self._on_diagnostics)
        for name in ("tare", "detect_hover", "reset"):
            rospy.wait_for_service(node + "/" + name, timeout=30.0)
        self.wait_for(lambda: self.rc_out_pub.get_num_connections() > 0, 10.0, "the node subscribing to rc/out")
        self.stamp = rospy.Time.now()

    def _keep(self, message, store):
        with self._lock:
            store.append(message)

    def _on_diagnostics(self, message):
        with self._lock:
            for status in message.status:
                self.diagnostics[status.name.split(": ", 1)[-1]] = status

    def call(self, service):
        return rospy.ServiceProxy(self.node + "/" + service, Trigger)()

    def battery(self, voltage_v):
        self.battery_pub.publish(BatteryState(voltage=voltage_v))

    def rc_out(self, channels, stamp=None):
        message = RCOut(channels=list(channels))
        if stamp is None:
            self.stamp = max(rospy.Time.now(), self.stamp + rospy.Duration(0.001))
            stamp = self.stamp
        message.header.stamp = stamp
        self.rc_out_pub.publish(message)

    def fly(self, channels, seconds, voltage_v=None, rate_hz=50.0):
        """RCOut at rate_hz for `seconds`, with a battery message every second if voltage_v is given."""
        rate = rospy.Rate(rate_hz)
        end = rospy.Time.now() + rospy.Duration(seconds)
        last_battery = None
        while rospy.Time.now() < end and not rospy.is_shutdown():
            if voltage_v is not None and (last_battery is None or (rospy.Time.now() - last_battery).to_sec() >= 1.0):
                self.battery(voltage_v)
                last_battery = rospy.Time.now()
            self.rc_out(channels)
            rate.sleep()

    def count(self, store):
        with self._lock:
            return len(store)

    def latest(self, store):
        with self._lock:
            return store[-1] if store else None

    def diagnostic(self, name):
        with self._lock:
            return self.diagnostics.get(name)

    @staticmethod
    def wait_for(condition, timeout_s, what):
        end = rospy.Time.now() + rospy.Duration(timeout_s)
        while not condition():
            if rospy.Time.now() > end or rospy.is_shutdown():
                raise AssertionError("timed out waiting for " + what)
            rospy.sleep(0.05)

    def wait_for_diagnostic(self, name, text, timeout_s=5.0):
        """Waits until the status `name` has `text` in its message; returns the status."""
        def matches():
            status = self.diagnostic(name)
            return status is not None and text in status.message
        try:
            self.wait_for(matches, timeout_s, "diagnostic '%s' saying '%s'" % (name, text))
        except AssertionError:
            status = self.diagnostic(name)
            raise AssertionError("diagnostic '%s' never said '%s'; last: %s" %
                                 (name, text, status.message if status else "none"))
        return self.diagnostic(name)


def node_diagnostics(node_name):
    """Subscribes to /diagnostics for the node whose name ends in `node_name`: returns the dict of
    its newest status per task (filled as they come) and the subscriber, to unregister."""
    statuses = {}

    def on_diagnostics(message):
        for status in message.status:
            node, _, task = status.name.partition(": ")
            if node.endswith(node_name):
                statuses[task] = status

    return statuses, rospy.Subscriber("/diagnostics", DiagnosticArray, on_diagnostics)


def wait_until(condition, timeout_s, what, poll_s=0.05):
    """Polls `condition` on the wall clock until it holds; AssertionError naming `what` after
    `timeout_s` (for tests that drive time themselves, where ROS time may stand still)."""
    end = time.monotonic() + timeout_s
    while not condition():
        if time.monotonic() > end:
            raise AssertionError("timed out waiting for " + what)
        time.sleep(poll_s)


def is_nan(value):
    return isinstance(value, float) and math.isnan(value)
