#!/usr/bin/env python3
"""estimator_node killed with SIGKILL in the middle of ~tare calls, many times, and restarted: the
tare file is always the old tare or the new one, never a broken file, never moved aside as
unreadable, and the restarted node always takes it (never a silent default)."""
import glob
import os
import random
import shutil
import signal
import subprocess
import tempfile
import threading
import time
import unittest

import roslib.packages
import rospy
import rostest
import yaml
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from propulsion_estimator.msg import PayloadEstimate
from sensor_msgs.msg import BatteryState
from std_srvs.srv import Trigger

from estimator_harness import wait_until
from rcout import RCOut

NODE = "/killed_estimator"
VOLTAGE_V = 11.4


class Flight(threading.Thread):
    """RCOut at 100 Hz at one PWM and a voltage every half second, until stopped."""

    def __init__(self, rc_out_pub, battery_pub, pwm_us):
        super().__init__(daemon=True)
        self.rc_out_pub, self.battery_pub, self.pwm_us = rc_out_pub, battery_pub, pwm_us
        self.stopped = threading.Event()

    def run(self):
        tick = 0
        while not self.stopped.wait(0.01):
            if tick % 50 == 0:
                self.battery_pub.publish(BatteryState(voltage=VOLTAGE_V))
            message = RCOut(channels=[self.pwm_us] * 4 + [1000] * 4)
            message.header.stamp = rospy.Time.now()
            self.rc_out_pub.publish(message)
            tick += 1


class TareKillTest(unittest.TestCase):
    def setUp(self):
        rospy.init_node("test_tare_kill")
        self.kills = rospy.get_param("~kills")
        self.max_kill_delay_s = rospy.get_param("~max_kill_delay_s")
        self.rng = random.Random(rospy.get_param("~seed"))
        self.folder = tempfile.mkdtemp(prefix="pe_tare_kill_")
        self.tare_file = os.path.join(self.folder, "tare.yaml")
        self.binary = roslib.packages.find_node("propulsion_estimator", "estimator_node")[0]
        for name, value in (("model", rospy.get_param("~model")), ("tare_file", self.tare_file),
                            ("imu_topic", ""), ("velocity_topic", ""), ("hover/window_s", 0.5),
                            ("diagnostic_period", 0.2)):
            rospy.set_param(NODE + "/" + name, value)
        self.node = None

    def tearDown(self):
        if self.node is not None and self.node.poll() is None:
            self.node.kill()
            self.node.wait()
        shutil.rmtree(self.folder)

    def read_tare_file(self):
        """The tare file's empty mass, None when there is none; fails on a broken file."""
        if not os.path.exists(self.tare_file):
            return None
        with open(self.tare_file) as f:
            text = f.read()
        content = yaml.safe_load(text)
        self.assertIsInstance(content, dict, "broken tare file: %r" % text)
        self.assertEqual(sorted(content), ["empty_mass_kg", "model", "model_fingerprint"],
                         "broken tare file: %r" % text)
        self.assertIsInstance(content["empty_mass_kg"], float, "broken tare file: %r" % text)
        return content["empty_mass_kg"]

    def start_node(self, run):
        """Starts the node on inputs of its own (a killed node's connections may linger)."""
        rc_out_topic, battery_topic = "/run%d/rc_out" % run, "/run%d/battery" % run
        rospy.set_param(NODE + "/rc_out_topic", rc_out_topic)
        rospy.set_param(NODE + "/battery_topic", battery_topic)
        rc_out_pub = rospy.Publisher(rc_out_topic, RCOut, queue_size=100)
        battery_pub = rospy.Publisher(battery_topic, BatteryState, queue_size=10)
        self.node = subprocess.Popen([self.binary, "__name:=" + NODE.lstrip("/")], stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL)
        rospy.wait_for_service(NODE + "/tare", timeout=60.0)
        wait_until(lambda: rc_out_pub.get_num_connections() > 0 and battery_pub.get_num_connections() > 0, 30.0,
                  "node %d subscribing to its inputs" % run)
        return rc_out_pub, battery_pub

    def test_kill_during_tare_writes(self):
        tare_calls = runs_killed_before_an_answer = 0
        pwm_us = 1600
        old_kg = None  # what the file holds
        # At least `kills` kills, and on until one has landed inside a write (between the temporary
        # file's creation and its rename, which leaves it behind), up to three times as many.
        run, kills = 0, 0
        # Temporary files seen after a start: a start removes those older than a minute.
        left_by_kills = set()
        while True:
            payloads, statuses = [], {}

            def on_diagnostics(message):
                for status in message.status:
                    # diagnostic_updater's placeholder before the first update is no verdict.
                    if status.name == NODE.lstrip("/") + ": Tare file" and status.message != "Node starting up":
                        statuses["Tare file"] = status

            payload_sub = rospy.Subscriber(NODE + "/payload", PayloadEstimate, payloads.append)
            diagnostics_sub = rospy.Subscriber("/diagnostics", DiagnosticArray, on_diagnostics)
            rc_out_pub, battery_pub = self.start_node(run)
            pwm_us = 1600 + (pwm_us - 1600 + self.rng.randrange(1, 150)) % 150  # another tare each run
            flight = Flight(rc_out_pub, battery_pub, pwm_us)
            flight.start()
            try:
                # The restarted node took the file's tare, or said it has none.
                wait_until(lambda: payloads, 30.0, "an estimate of node %d" % run)
                payload = payloads[-1]
                if old_kg is None:
                    self.assertEqual(payload.empty_mass_source, "none")
                else:
                    self.assertEqual(payload.empty_mass_source, "tare_file", "run %d" % run)
                    self.assertEqual(payload.empty_mass_kg, old_kg, "run %d" % run)
                    wait_until(lambda: "Tare file" in statuses, 30.0, "the Tare file diagnostic of node %d" % run)
                    status = statuses["Tare file"]
                    self.assertEqual(status.level, DiagnosticStatus.OK, status.message)
                    self.assertTrue(status.message.startswith(self.tare_file + ": empty mass "), status.message)
                inside_a_write = glob.glob(self.tare_file + ".tmp-*")
                left_by_kills.update(inside_a_write)
                if kills >= 3 * self.kills or (kills >= self.kills and inside_a_write):
                    break

                # Hovering long enough for a tare, then ~tare again and again until the kill.
                wait_until(lambda: payloads[-1].hovering and payloads[-1].window_samples >= 25, 30.0,  # min_samples
                          "a hover of node %d" % run)
                new_kg = payloads[-1].total_mass_kg
                answers = []

                def tare_again_and_again():
                    tare = rospy.ServiceProxy(NODE + "/tare", Trigger)
                    try:
                        while True:
                            answers.append(tare())
                    except (rospy.ServiceException, OSError):
                        pass  # killed

                caller = threading.Thread(target=tare_again_and_again, daemon=True)
                caller.start()
                time.sleep(self.rng.uniform(0.0, self.max_kill_delay_s))
                self.node.send_signal(signal.SIGKILL)
                self.node.wait()
                kills += 1
                caller.join(30.0)
            finally:
                flight.stopped.set()
                flight.join()
                payload_sub.unregister()
                diagnostics_sub.unregister()
                rc_out_pub.unregister()
                battery_pub.unregister()

            tare_calls += len(answers)
            succeeded = [a for a in answers if a.success]
            # A ~tare may be refused when this test's publisher stalls under load and leaves the
            # short hover window unfilled ("refused: not hovering: ..."); never because the write
            # failed (an answer "empty mass ..., applies to this run only: ...").
            refused = [a.message for a in answers if not a.success]
            self.assertTrue(all(message.startswith("refused: ") for message in refused), refused)
            runs_killed_before_an_answer += not answers
            read_kg = self.read_tare_file()
            self.assertEqual(glob.glob(self.tare_file + ".bad-*"), [], "a tare file was moved aside")
            # Old or new; the new one for certain once a ~tare answered (it answers after the rename).
            if old_kg is not None or succeeded:
                self.assertIsNotNone(read_kg, "run %d: the tare file vanished" % run)
            if succeeded:
                self.assertAlmostEqual(read_kg, new_kg, delta=1e-9)
            elif read_kg != old_kg:
                self.assertAlmostEqual(read_kg, new_kg, delta=1e-9, msg="neither the old tare %r nor the new %r" %
                                       (old_kg, new_kg))
            rospy.loginfo("tare_kill: run %d: %d ~tare answered, file %s (old %s, new %s)", run, len(answers),
                          read_kg, old_kg, new_kg)
            old_kg = read_kg
            run += 1
        self.assertEqual(glob.glob(self.tare_file + ".bad-*"), [], "the last start moved the tare file aside")
        leftovers = left_by_kills | set(glob.glob(self.tare_file + ".tmp-*"))
        rospy.loginfo("tare_kill: %d kills (%d before their run's first ~tare answer), %d ~tare answered; %d "
                      "temporary files left by the kills", kills, runs_killed_before_an_answer, tare_calls,
                      len(leftovers))
        self.assertGreater(len(leftovers), 0, "no kill landed inside a write in %d kills" % kills)
        # Tares were written, and some kills came after one had been answered (not all before the first).
        self.assertGreater(tare_calls, 0)
        self.assertGreater(kills - runs_killed_before_an_answer, 0)


if __name__ == "__main__":
    rostest.rosrun("propulsion_estimator", "tare_kill", TareKillTest)
