#!/usr/bin/env python3
"""rostest of estimator_node as a black box: inputs on MAVROS topics, estimates on ~motors,
~totals and ~payload, services, /diagnostics. Expected values come as test parameters."""
import glob
import os
import shutil
import tempfile
import unittest

import rosgraph
import roslaunch
import rospy
import rostest
import yaml
from diagnostic_msgs.msg import DiagnosticStatus
from propulsion_estimator.msg import PayloadEstimate
from sensor_msgs.msg import BatteryState, Imu, Range

from estimator_harness import EstimatorHarness, is_nan, node_diagnostics

G = 9.80665
HOVER = [1690, 1690, 1690, 1690, 1000, 1000, 1000, 1000]
# Every effect of model/model_effects.h, appended to the thesis model for test_7.
ALL_EFFECTS = """effects:
  supply_resistance: {resistance_ohm: 0.035}
  ground_effect: {coefficient_m2: 0.0011, rotor_height_m: 0.05}
  motor_temperature: {per_c: 0.0012, reference_c: 22}
  air_density: {full_thrust_exponent: 0.85}
  thrust_loss: {fraction: 0.04}
  climb_inflow: {per_m_s: 0.03}
  esc_offset: {offset_us: 12}
"""
EFFECT_TOPICS = ("/mavros/imu/static_pressure", "/mavros/imu/temperature_baro", "/mavros/rangefinder/rangefinder",
                 "/motor_temperature")


class EstimatorNodeTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_estimator_node")
        cls.h = EstimatorHarness()
        cls.thrust_n = rospy.get_param("~expected_thrust_per_motor_n")
        cls.tolerance_n = rospy.get_param("~thrust_tolerance_n")
        cls.tare_file = rospy.get_param("~tare_file")
        assert not os.path.exists(cls.tare_file), "a tare file from another run: " + cls.tare_file

    def assert_no_estimate_from(self, publish, diagnostic_text, level=DiagnosticStatus.WARN):
        """Publishes a bad input (again every 0.3 s, in case one is lost on a loaded machine) until the
        diagnostics say why it was refused, and checks that no estimate followed."""
        before = self.h.count(self.h.motors)
        end = rospy.Time.now() + rospy.Duration(10.0)
        while True:
            self.h.battery(11.4)  # keep the voltage fresh: a stale battery is refused first
            rospy.sleep(0.05)
            publish()
            rospy.sleep(0.3)
            status = self.h.diagnostic("Motor outputs")
            if status is not None and diagnostic_text in status.message:
                break
            self.assertLess(rospy.Time.now(), end, "diagnostic never said '%s'; last: %s" %
                            (diagnostic_text, status.message if status else "none"))
        self.assertEqual(self.h.count(self.h.motors), before, "an estimate was published from a bad input")
        self.assertEqual(status.level, level)

    def assert_tare_survives_a_restart(self, empty_mass_kg):
        """A second estimator started with the same tare file begins with the persisted tare."""
        for name in ("model", "tare_file"):
            rospy.set_param("/restarted/" + name, rospy.get_param("/propulsion_estimator/" + name))
        launch = roslaunch.scriptapi.ROSLaunch()
        launch.start()
        process = launch.launch(roslaunch.core.Node("propulsion_estimator", "estimator_node", name="restarted",
                                                    namespace="/", output="log"))
        try:
            received = []
            subscriber = rospy.Subscriber("/restarted/payload", PayloadEstimate, received.append)
            rospy.wait_for_service("/restarted/tare", timeout=30.0)
            # Both inputs connected before flying: a battery message sent before the restarted node's
            # subscription is up is lost, and without a voltage it estimates nothing.
            self.h.wait_for(lambda: self.h.rc_out_pub.get_num_connections() > 1
                            and self.h.battery_pub.get_num_connections() > 1, 10.0, "the restarted node")
            self.h.fly(HOVER, 1.0, voltage_v=11.4)
            self.h.wait_for(lambda: received, 5.0, "an estimate of the restarted node")
            self.assertEqual(received[-1].empty_mass_source, "tare_file")
            self.assertAlmostEqual(received[-1].empty_mass_kg, empty_mass_kg, places=9)
            subscriber.unregister()
        finally:
            process.stop()
            launch.stop()

    def test_1_no_estimate_before_any_battery_voltage(self):
        self.h.fly(HOVER, 1.0)
        self.assertEqual(self.h.count(self.h.motors), 0)
        status = self.h.wait_for_diagnostic("Inputs", "estimates stopped: no valid battery voltage received")
        self.assertEqual(status.level, DiagnosticStatus.ERROR)

    def test_2_hover_estimates(self):
        self.h.fly(HOVER, 4.0, voltage_v=11.4)
        motors = self.h.latest(self.h.motors)
        self.assertEqual([m.channel for m in motors.motors], [1, 2, 3, 4])
        self.assertAlmostEqual(motors.voltage_v, 11.4, places=5)
        for m in motors.motors:
            self.assertEqual(m.pwm_us, 1690.0)
            self.assertAlmostEqual(m.thrust_n, self.thrust_n, delta=self.tolerance_n)
            self.assertTrue(m.in_domain)
            self.assertGreater(m.current_a, 0.0)
            self.assertAlmostEqual(m.efficiency_n_per_w, m.thrust_n / m.power_w, places=9)
        totals = self.h.latest(self.h.totals)
        self.assertAlmostEqual(totals.mass_kg, 4 * self.thrust_n / G, delta=4 * self.tolerance_n / G)
        self.assertEqual(totals.motors_out_of_domain, 0)
        payload = self.h.latest(self.h.payload)
        self.assertTrue(payload.hovering)
        self.assertEqual(payload.state, "no_tare_yet")
        self.assertAlmostEqual(payload.total_mass_kg, totals.mass_kg, places=6)
        self.assertTrue(is_nan(payload.payload_mass_kg))
        self.assertGreater(payload.window_samples, 50)

    def test_2_capability(self):
        """~capability at 1 Hz from its own timer: the payload limit at the model's top PWM, and
        NaN with the reason for the endurance without a configured battery."""
        self.h.fly(HOVER, 4.0, voltage_v=11.4)
        before = self.h.count(self.h.capability)
        self.h.wait_for(lambda: self.h.count(self.h.capability) > before, 3.0, "a ~capability message")
        c = self.h.latest(self.h.capability)
        mass = self.h.latest(self.h.payload).total_mass_kg
        self.assertAlmostEqual(c.hover_mass_kg, mass, places=6)
        self.assertEqual(c.pwm_max_us, 1900.0)
        self.assertGreater(c.max_thrust_n, 4 * self.thrust_n)
        self.assertAlmostEqual(c.thrust_to_weight, c.max_thrust_n / (mass * G), places=9)
        self.assertAlmostEqual(c.max_additional_payload_kg, c.max_thrust_n / (1.6 * G) - mass, places=9)
        self.assertTrue(is_nan(c.hover_endurance_s))
        self.assertEqual(c.endurance_basis, "no battery capacity configured (capability/battery/capacity_ah, cells)")
        self.assertFalse(c.motor_health_judged)
        self.assertEqual(c.motor_health_note, "no rotor geometry (a URDF is needed)")  # this node has no URDF
        status = self.h.wait_for_diagnostic("Capability", "max additional payload %.3f kg" % c.max_additional_payload_kg)
        self.assertEqual(status.level, DiagnosticStatus.OK)

    def test_3_services(self):
        self.h.fly(HOVER, 3.0, voltage_v=11.4)
        answer = self.h.call("detect_hover")
        self.assertTrue(answer.success, answer.message)
        self.assertTrue(answer.message.startswith("hovering; window"), answer.message)
        answer = self.h.call("tare")
        self.assertTrue(answer.success, answer.message)
        self.assertIn("saved to " + self.tare_file, answer.message)
        with open(self.tare_file) as f:
            self.assertIn("empty_mass_kg: ", f.read())
        self.h.fly(HOVER, 0.5, voltage_v=11.4)
        payload = self.h.latest(self.h.payload)
        self.assertEqual(payload.state, "hovering")
        self.assertEqual(payload.empty_mass_source, "tare")
        self.assertAlmostEqual(payload.payload_mass_kg, 0.0, delta=1e-6)
        self.assert_tare_survives_a_restart(payload.empty_mass_kg)
        answer = self.h.call("reset")
        self.assertTrue(answer.success)
        self.assertEqual(answer.message, "windows and tare cleared; empty mass now unknown (source: none)")
        self.assertFalse(os.path.exists(self.tare_file))
        status = self.h.wait_for_diagnostic("Tare file", self.tare_file + ": removed by ~reset")
        self.assertEqual(status.level, DiagnosticStatus.OK)
        self.h.fly(HOVER, 0.2, voltage_v=11.4)
        self.assertEqual(self.h.latest(self.h.payload).state, "waiting_for_hover")
        answer = self.h.call("tare")
        self.assertFalse(answer.success)
        self.assertTrue(answer.message.startswith("refused: not hovering: window spans"), answer.message)

    def test_4_bad_messages(self):
        self.h.fly(HOVER, 1.0, voltage_v=11.4)
        for bad_voltage, text in ((float("nan"), "battery voltage nan V refused"),
                                  (0.0, "battery voltage 0 V refused")):
            self.h.battery(bad_voltage)
            self.h.wait_for_diagnostic("Motor outputs", text)
            self.h.fly(HOVER, 0.3)
            totals = self.h.latest(self.h.totals)
            self.assertAlmostEqual(totals.voltage_v, 11.4, places=5, msg="an estimate used the bad voltage")
            self.h.fly(HOVER, 1.5, voltage_v=11.4)  # the next diagnostics period is clean again
        # Disarmed on the ground is normal: no estimates, said plainly, not a warning.
        self.assert_no_estimate_from(lambda: self.h.rc_out([0, 0, 0, 0, 0, 0, 0, 0]),
                                     "channel 1 at 0 us, at or below disarmed_pwm_max_us 950", DiagnosticStatus.OK)
        self.assert_no_estimate_from(lambda: self.h.rc_out([900, 900, 900, 900, 900, 900, 900, 900]),
                                     "channel 1 at 900 us, at or below disarmed_pwm_max_us 950", DiagnosticStatus.OK)
        self.assert_no_estimate_from(lambda: self.h.rc_out([1690, 1690, 1690]),
                                     "RCOut has 3 channels, motor channel 4 is configured")
        self.h.fly(HOVER, 0.5, voltage_v=11.4)
        self.assert_no_estimate_from(lambda: self.h.rc_out(HOVER, stamp=self.h.stamp - rospy.Duration(1.0)),
                                     "stamp went back by 1 s")
        # Still alive and estimating.
        before = self.h.count(self.h.motors)
        self.h.fly(HOVER, 0.5, voltage_v=11.4)
        self.assertGreater(self.h.count(self.h.motors), before + 10)

    def test_5_imu_without_orientation_is_skipped(self):
        imu = rospy.Publisher("/mavros/imu/data", Imu, queue_size=10)
        self.h.wait_for(lambda: imu.get_num_connections() > 0, 10.0, "the node subscribing to the IMU")
        message = Imu()
        message.orientation_covariance[0] = -1.0  # REP-145: no orientation
        message.linear_acceleration.z = 9.81
        for _ in range(5):
            imu.publish(message)
            self.h.fly(HOVER, 0.1, voltage_v=11.4)
        # Counted as carrying no orientation, not refused as a bad IMU, and not used.
        self.h.wait_for(lambda: int({kv.key: kv.value for kv in self.h.diagnostic("Inputs").values}
                                    ["imu messages without orientation"]) > 0, 5.0, "the IMU messages counted")
        outputs = {kv.key: kv.value for kv in self.h.wait_for_diagnostic("Motor outputs", "").values}
        self.assertEqual(outputs["rejected bad_imu"], "0")
        totals = self.h.latest(self.h.totals)
        self.assertAlmostEqual(totals.vertical_thrust_n, totals.thrust_n, places=9)

    def test_6_stale_battery_stops_estimates(self):
        self.h.fly(HOVER, 1.0, voltage_v=11.4)
        timeout = rospy.get_param("/propulsion_estimator/battery_timeout_s")
        self.h.fly(HOVER, timeout + 0.5)  # no battery messages any more
        before = self.h.count(self.h.motors)
        self.h.fly(HOVER, 0.5)
        self.assertEqual(self.h.count(self.h.motors), before)
        status = self.h.wait_for_diagnostic("Inputs", "estimates stopped: no battery voltage for")
        self.assertEqual(status.level, DiagnosticStatus.ERROR)

    def test_7_hardware_id_names_the_combination(self):
        with open(rospy.get_param("/propulsion_estimator/model")) as f:
            meta = yaml.safe_load(f)["metadata"]
        status = self.h.wait_for_diagnostic("Payload", "")
        self.assertEqual(status.hardware_id, "%s / %s / %s" % (meta["esc"], meta["motor"], meta["propeller"]))

    def test_8_effect_topics_and_diagnostic(self):
        """A node whose model has every effect subscribes to each effect's topic (the node with the
        plain model to none of them) and names, in its Effects diagnostic, each correction whose
        signal is missing."""
        folder = tempfile.mkdtemp(prefix="pe_effects_")
        self.addCleanup(shutil.rmtree, folder, True)
        model = os.path.join(folder, "all_effects.yaml")
        with open(rospy.get_param("/propulsion_estimator/model")) as f:
            text = f.read()
        with open(model, "w") as f:
            f.write(text + "\n" + ALL_EFFECTS)
        rospy.set_param("/effects_node/model", model)
        statuses, diagnostics = node_diagnostics("effects_node")

        def subscribers(topic):
            return dict(rosgraph.Master("/test_estimator_node").getSystemState()[1]).get(topic, [])

        def effects_message():
            return statuses["Effects"].message if "Effects" in statuses else "none"

        launch = roslaunch.scriptapi.ROSLaunch()
        launch.start()
        process = launch.launch(roslaunch.core.Node("propulsion_estimator", "estimator_node", name="effects_node",
                                                    namespace="/", output="log"))
        try:
            rospy.wait_for_service("/effects_node/tare", timeout=30.0)
            self.h.wait_for(lambda: all("/effects_node" in subscribers(t) for t in EFFECT_TOPICS), 10.0,
                            "the subscriptions to the effects' topics")
            # The plain node reads only the barometer, for the hover check's vertical speed.
            for topic in EFFECT_TOPICS:
                if topic == "/mavros/imu/static_pressure":
                    self.assertIn("/propulsion_estimator", subscribers(topic))
                else:
                    self.assertNotIn("/propulsion_estimator", subscribers(topic))

            # The battery's current (0 A in the harness's messages) is fresh, the other signals missing.
            missing = ("air_density (air density on /mavros/imu/static_pressure and "
                       "/mavros/imu/temperature_baro missing or stale), ground_effect (height above the ground on "
                       "/mavros/rangefinder/rangefinder missing or stale), motor_temperature (motor temperature on "
                       "/motor_temperature missing or stale), climb_inflow (speed along the rotors' axes on "
                       "/mavros/local_position/velocity_local and /mavros/imu/data missing or stale)")
            expected = "skipped: " + missing + "; applied: supply_resistance, thrust_loss, esc_offset"
            end = rospy.Time.now() + rospy.Duration(10.0)
            while effects_message() != expected:
                self.assertLess(rospy.Time.now(), end, "Effects diagnostic: " + effects_message())
                self.h.battery(11.4)
                rospy.sleep(0.2)
            self.assertEqual(statuses["Effects"].level, DiagnosticStatus.WARN)

            # A rangefinder: ground_effect moves to the applied corrections.
            ranges = rospy.Publisher("/mavros/rangefinder/rangefinder", Range, queue_size=10)
            expected = expected.replace("ground_effect (height above the ground on /mavros/rangefinder/rangefinder "
                                        "missing or stale), ", "").replace(
                "applied: supply_resistance", "applied: supply_resistance, ground_effect")
            end = rospy.Time.now() + rospy.Duration(10.0)
            while effects_message() != expected:
                self.assertLess(rospy.Time.now(), end, "Effects diagnostic: " + effects_message())
                self.h.battery(11.4)
                ranges.publish(Range(range=1.0, min_range=0.1, max_range=12.0))
                rospy.sleep(0.05)
        finally:
            diagnostics.unregister()
            process.stop()
            launch.stop()

    def test_9_a_hover_verdict_expires_when_inputs_stop(self):
        """rc/out and the battery stop after a hover: once hover/window_s has passed without an
        accepted message, the verdict is no hover and ~tare refuses the stale average."""
        self.h.fly(HOVER, 3.0, voltage_v=11.4)
        rospy.sleep(rospy.get_param("/propulsion_estimator/hover/window_s") + 0.5)
        answer = self.h.call("detect_hover")
        self.assertFalse(answer.success, answer.message)
        self.assertIn("(the last verdict expired)", answer.message)
        answer = self.h.call("tare")
        self.assertFalse(answer.success, answer.message)
        self.assertTrue(answer.message.startswith("refused: no motor outputs accepted for "), answer.message)
        self.assertTrue(answer.message.endswith("the last hover verdict expired"), answer.message)
        self.assertFalse(os.path.exists(self.tare_file))


    def test_9_tare_file_that_cannot_be_written_or_removed(self):
        """~tare and ~reset answer failure, with the reason, when the tare file cannot be written or
        removed, and the Tare file diagnostic warns."""
        # A non-empty folder where the tare file goes: it can be neither replaced nor removed.
        os.makedirs(os.path.join(self.tare_file, "in_the_way"))
        try:
            self.h.fly(HOVER, 3.0, voltage_v=11.4)
            answer = self.h.call("tare")
            self.assertFalse(answer.success, answer.message)
            reason = self.tare_file + ": tare file not written: cannot replace it with the temporary file: Is a directory"
            self.assertTrue(answer.message.startswith("empty mass "), answer.message)
            self.assertTrue(answer.message.endswith(", applies to this run only: " + reason), answer.message)
            status = self.h.wait_for_diagnostic("Tare file", "~tare not persisted: " + reason)
            self.assertEqual(status.level, DiagnosticStatus.WARN)
            self.assertEqual(glob.glob(self.tare_file + ".tmp*"), [])
            answer = self.h.call("reset")
            self.assertFalse(answer.success, answer.message)
            self.assertEqual(answer.message, "windows and tare cleared; empty mass now unknown (source: none); but " +
                             self.tare_file + ": cannot remove the tare file: Directory not empty, and the next start "
                             "reads it again")
            status = self.h.wait_for_diagnostic("Tare file", "~reset: " + self.tare_file)
            self.assertEqual(status.level, DiagnosticStatus.WARN)
        finally:
            shutil.rmtree(self.tare_file)

    def tare_file_status(self, name, tare_file):
        """The Tare file diagnostic of a node `name` started with `tare_file`, once it is up; asserts
        that it keeps running, then stops it."""
        rospy.set_param("/%s/model" % name, rospy.get_param("/propulsion_estimator/model"))
        rospy.set_param("/%s/tare_file" % name, tare_file)
        statuses, diagnostics = node_diagnostics(name)
        launch = roslaunch.scriptapi.ROSLaunch()
        launch.start()
        process = launch.launch(roslaunch.core.Node("propulsion_estimator", "estimator_node", name=name,
                                                    namespace="/", output="log"))
        try:
            rospy.wait_for_service("/%s/tare" % name, timeout=30.0)
            self.h.wait_for(lambda: "Tare file" in statuses, 10.0, "the Tare file diagnostic of the node")
            self.assertTrue(process.is_alive())
            return statuses["Tare file"]
        finally:
            diagnostics.unregister()
            process.stop()
            launch.stop()

    def test_9_tare_file_that_cannot_be_read_is_moved_aside(self):
        """A node whose tare file is empty starts without it (the launch marks it required: it must
        not stop), moves the file aside and names it and the reason on its Tare file diagnostic."""
        folder = tempfile.mkdtemp(prefix="pe_bad_tare_")
        self.addCleanup(shutil.rmtree, folder, True)
        bad = os.path.join(folder, "tare.yaml")
        open(bad, "w").close()
        status = self.tare_file_status("bad_tare", bad)
        aside = glob.glob(bad + ".bad-*")
        self.assertEqual(len(aside), 1, aside)
        self.assertFalse(os.path.exists(bad))
        self.assertEqual(status.level, DiagnosticStatus.WARN)
        self.assertEqual(status.message, "refused: " + bad + ": the file is empty; started without the tare, the "
                         "file moved to " + aside[0])

    def test_9_tare_file_that_is_a_folder_is_left_where_it_is(self):
        """A folder named as the tare file is refused by name on the Tare file diagnostic; the node
        starts without the tare and leaves the folder, the user's, where it is."""
        folder = tempfile.mkdtemp(prefix="pe_folder_tare_")
        self.addCleanup(shutil.rmtree, folder, True)
        status = self.tare_file_status("folder_tare", folder)
        self.assertEqual(status.level, DiagnosticStatus.WARN)
        self.assertEqual(status.message, "refused: " + folder + ": a folder, not a file; started without the tare")
        self.assertTrue(os.path.isdir(folder))
        self.assertEqual(glob.glob(folder + ".bad-*"), [])

    def test_9_pack_file_learned_from_a_flight_and_read_at_the_next_start(self):
        """A node with a pack file and no pack_id takes the pack's identity from the battery's serial
        number, writes the pack's record once the flight has landed and rested 10 s, and a node
        started later reads it for the same pack."""
        folder = tempfile.mkdtemp(prefix="pe_pack_")
        self.addCleanup(shutil.rmtree, folder, True)
        path = os.path.join(folder, "SN-1.yaml")
        statuses, diagnostics = node_diagnostics("packed")

        def start():
            for key, value in (("model", rospy.get_param("/propulsion_estimator/model")),
                               ("capability/battery/capacity_ah", 4.0), ("capability/battery/cells", 3),
                               ("capability/battery/pack_file", os.path.join(folder, "{pack_id}.yaml")),
                               ("battery_topic", "/packed_battery")):
                rospy.set_param("/packed/" + key, value)
            launch = roslaunch.scriptapi.ROSLaunch()
            launch.start()
            process = launch.launch(roslaunch.core.Node("propulsion_estimator", "estimator_node", name="packed",
                                                        namespace="/", output="log"))
            rospy.wait_for_service("/packed/tare", timeout=30.0)
            return launch, process

        publisher = rospy.Publisher("/packed_battery", BatteryState, queue_size=50)
        launch, process = start()
        try:
            self.h.wait_for(lambda: publisher.get_num_connections() > 0, 10.0, "the node's battery subscription")
            self.h.wait_for(lambda: "Pack file" in statuses, 10.0, "the Pack file diagnostic")
            self.assertEqual(statuses["Pack file"].level, DiagnosticStatus.WARN)
            self.assertTrue(statuses["Pack file"].message.startswith("no pack identity yet"))
            rate = rospy.Rate(10.0)

            def publish(voltage_v, current_a, seconds):
                for _ in range(int(10 * seconds)):
                    publisher.publish(BatteryState(voltage=voltage_v, current=current_a, serial_number="SN-1"))
                    rate.sleep()
            for voltage_v, current_a, seconds in ((12.4, 0.5, 3.0), (11.9, 14.0, 4.0), (12.3, 0.5, 3.0)):
                publish(voltage_v, current_a, seconds)
            # Landed and resting: the diagnostic says the flight is learned once the rest is long enough.
            self.h.wait_for(lambda: "landed: this flight is learned once the pack has rested" in
                            statuses["Pack file"].message, 10.0, "the Pack file diagnostic of a landed flight")
            self.assertEqual(statuses["Pack file"].level, DiagnosticStatus.OK)
            self.assertFalse(os.path.exists(path))
            publish(12.3, 0.5, 9.0)
            self.h.wait_for(lambda: os.path.exists(path), 10.0, "the pack file " + path)
            with open(path) as f:
                record = yaml.safe_load(f)
            self.assertEqual(record["pack_id"], "SN-1")
            self.assertEqual(record["cells"], 3)
            self.assertEqual(record["flights"], 1)
            self.assertEqual(glob.glob(path + ".tmp*"), [])
            process.stop()
            launch.stop()
            statuses.clear()
            launch, process = start()
            self.h.wait_for(lambda: publisher.get_num_connections() > 0, 10.0, "the restarted node's subscription")
            publisher.publish(BatteryState(voltage=12.4, current=0.5, serial_number="SN-1"))
            self.h.wait_for(lambda: "Pack file" in statuses and statuses["Pack file"].message.endswith(
                "1 flights learned"), 10.0, "the restarted node's Pack file diagnostic")
            self.assertEqual(statuses["Pack file"].message, path + ": pack \"SN-1\", 1 flights learned")
            self.assertEqual(statuses["Pack file"].level, DiagnosticStatus.OK)
        finally:
            diagnostics.unregister()
            process.stop()
            launch.stop()
            shutil.rmtree(folder)


if __name__ == "__main__":
    rostest.rosrun("propulsion_estimator", "estimator_node", EstimatorNodeTest)
