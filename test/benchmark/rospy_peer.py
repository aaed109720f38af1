#!/usr/bin/env python3
"""The end-to-end benchmark's reference peer (make bench, scripts/bench_node.py): the node a user
would write in rospy for the same job, to set estimator_node's cost beside.

For every mavros_msgs/RCOut it evaluates the model YAML's response surfaces (numpy, vectorised over
the motors) at the latest battery voltage: thrust, current, power, efficiency and rpm of each motor,
clamped to the model's domain, and the mass the summed thrust holds (no IMU: thrust / g). It
publishes them as ~motors (MotorEstimates) and ~totals (PropulsionTotals, stamped with the RCOut's
stamp, which the probe times). It does less than estimator_node: no hover detection, no payload
window, no diagnostics, no input checks beyond a voltage being known.

RCOut is received through a class genpy generates at start-up from the message's definition, as
if mavros_msgs were installed (Debian does not package it).

Parameters: ~model (model YAML), ~motor_channels (1-based), ~rc_out_topic, ~battery_topic."""
import sys

import genpy.dynamic
import numpy as np
import rospy
import yaml
from propulsion_estimator.msg import MotorEstimate, MotorEstimates, PropulsionTotals
from sensor_msgs.msg import BatteryState
from std_msgs.msg import Header

RCOUT_MD5SUM = "52cacf104bab5ae3b103cfe176590713"
RCOUT_DEFINITION = ("# RAW Servo out state\n\nstd_msgs/Header header\nuint16[] channels\n\n" + "=" * 80 +
                    "\nMSG: std_msgs/Header\n" + Header._full_text)
STANDARD_GRAVITY = 9.80665
TO_SI = {"thrust": {"N": 1.0, "g": STANDARD_GRAVITY / 1000.0, "kgf": STANDARD_GRAVITY},
         "current": {"A": 1.0}, "power": {"W": 1.0},
         "efficiency": {"N/W": 1.0, "g/W": STANDARD_GRAVITY / 1000.0}, "rpm": {"rpm": 1.0}}


class Surface:
    """sum(p_ij * x^i * v^j) in the output's unit, scaled to SI."""

    def __init__(self, polynomial, to_si):
        self.i = np.array([int(key[1]) for key in polynomial])
        self.j = np.array([int(key[2]) for key in polynomial])
        self.p = np.array([float(value) for value in polynomial.values()]) * to_si

    def __call__(self, x, v):
        return (self.p * np.power.outer(x, self.i) * np.power.outer(v, self.j)).sum(axis=1)


class Model:
    def __init__(self, path):
        with open(path) as f:
            document = yaml.safe_load(f)
        domain = document["domain"]
        self.pwm_range = domain["pwm_us"]
        self.voltage_range = domain["voltage_v"]
        self.surfaces = {}
        self.efficiency_derived = False
        for name, definition in document["outputs"].items():
            if "polynomial" in definition and "scaling" not in definition:
                self.surfaces[name] = Surface(definition["polynomial"], TO_SI[name][definition["unit"]])
            elif name == "efficiency" and definition.get("derived") == "thrust/power":
                self.efficiency_derived = True
            elif "none" not in definition:
                sys.exit("rospy_peer: %s: outputs.%s: only unscaled polynomials, none and efficiency as "
                         "thrust/power are supported" % (path, name))

    def evaluate(self, pwm_us, voltage_v):
        """Outputs of every motor in SI, a dict of arrays (NaN where the model has none)."""
        x = np.clip(pwm_us, *self.pwm_range)
        v = np.full_like(x, min(max(voltage_v, self.voltage_range[0]), self.voltage_range[1]))
        nan = np.full_like(x, np.nan)
        out = {name: np.maximum(surface(x, v), 0.0) for name, surface in self.surfaces.items()}
        if self.efficiency_derived:
            power = out["power"]
            out["efficiency"] = np.divide(out["thrust"], power, out=np.zeros_like(x), where=power > 0.0)
        for name in TO_SI:
            out.setdefault(name, nan)
        return out


class Peer:
    def __init__(self):
        rc_out_class = genpy.dynamic.generate_dynamic("mavros_msgs/RCOut", RCOUT_DEFINITION)["mavros_msgs/RCOut"]
        if rc_out_class._md5sum != RCOUT_MD5SUM:
            sys.exit("rospy_peer: generated mavros_msgs/RCOut has md5sum %s, not %s" % (rc_out_class._md5sum,
                                                                                        RCOUT_MD5SUM))
        self.model = Model(rospy.get_param("~model"))
        self.channels = np.array(rospy.get_param("~motor_channels"), dtype=int)
        self.domain = (self.model.pwm_range, self.model.voltage_range)
        self.voltage_v = None
        self.motors_pub = rospy.Publisher("~motors", MotorEstimates, queue_size=10)
        self.totals_pub = rospy.Publisher("~totals", PropulsionTotals, queue_size=10)
        rospy.Subscriber(rospy.get_param("~battery_topic", "/mavros/battery"), BatteryState, self.on_battery,
                         queue_size=5, tcp_nodelay=True)
        rospy.Subscriber(rospy.get_param("~rc_out_topic", "/mavros/rc/out"), rc_out_class, self.on_rc_out,
                         queue_size=20, tcp_nodelay=True)

    def on_battery(self, message):
        if np.isfinite(message.voltage) and message.voltage > 0.0:
            self.voltage_v = float(message.voltage)

    def on_rc_out(self, message):
        if self.voltage_v is None or len(message.channels) < self.channels.max():
            return
        pwm = np.array(message.channels, dtype=float)[self.channels - 1]
        out = self.model.evaluate(pwm, self.voltage_v)
        (pwm_lo, pwm_hi), (v_lo, v_hi) = self.domain
        in_domain = (pwm >= pwm_lo) & (pwm <= pwm_hi) & (v_lo <= self.voltage_v <= v_hi)

        motors = MotorEstimates(header=message.header, voltage_v=self.voltage_v)
        for k, channel in enumerate(self.channels):
            motors.motors.append(MotorEstimate(
                channel=int(channel), pwm_us=pwm[k], thrust_n=out["thrust"][k], current_a=out["current"][k],
                power_w=out["power"][k], efficiency_n_per_w=out["efficiency"][k], rpm=out["rpm"][k],
                in_domain=bool(in_domain[k]), measured_rpm=float("nan"), measured_current_a=float("nan"),
                rpm_ratio=float("nan"), current_ratio=float("nan")))
        self.motors_pub.publish(motors)

        thrust_n = float(out["thrust"].sum())
        power_w = float(out["power"].sum())
        self.totals_pub.publish(PropulsionTotals(
            header=message.header, voltage_v=self.voltage_v, thrust_n=thrust_n, vertical_thrust_n=thrust_n,
            current_a=float(out["current"].sum()), power_w=power_w,
            efficiency_n_per_w=thrust_n / power_w if power_w > 0.0 else 0.0,
            mass_kg=thrust_n / STANDARD_GRAVITY, thrust_centre_x_m=float("nan"), thrust_centre_y_m=float("nan"),
            motors_out_of_domain=int((~in_domain).sum())))


def main():
    rospy.init_node("rospy_peer")
    Peer()
    rospy.spin()


if __name__ == "__main__":
    main()
