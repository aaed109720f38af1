#!/usr/bin/env python3
"""Soak and faults: estimator_node driven at the rates of a PX4 vehicle (8-channel RCOut at 400 Hz,
BatteryState at 1 Hz) through cycles of faults, each held until /diagnostics names it and then
cleared: NaN, zero and negative voltages, disarmed PWM, fewer channels than configured, RCOut whose
channel count disagrees with its bytes, duplicated, backwards and far-future stamps, bursts and
silences of each topic; between the cycles single bad messages are mixed in at random. Checks: the
node never stops (same pid, alive), its resident memory stays flat, every good RCOut is accepted
and answered on ~totals at most once and no bad one is, the estimate after the faults equals the
one before, and the rates claimed were the rates sent.

A good RCOut whose answer never arrives passes only when the node counted it accepted, or when it was
sent while the node's process stood still:
- roscpp drops the oldest queued messages of a subscriber that falls more than the publisher's queue
  behind (this Python test on a loaded 2-core machine can): that loss is the transport's;
- a node not scheduled for seconds (a loaded CI machine: its /diagnostics stop and its process uses
  no CPU) reads, once it runs again, the RCOut that queued meanwhile before the voltage that queued
  beside them, and rightly finds its newest voltage older than battery_timeout_s (shown by stopping
  the node for 5 s: 1,595 refused as stale_battery). A node that stops its own diagnostics while
  busy (a computation blocking its threads) is not excused.
Both are reported and bounded (max_transport_loss, max_stall_s)."""
import collections
import os
import random
import struct
import time
import unittest
import xmlrpc.client

import rosgraph
import rospy
import rostest
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from propulsion_estimator.msg import PayloadEstimate, PropulsionTotals
from sensor_msgs.msg import BatteryState

from estimator_harness import wait_until
from rcout import RCOut

NODE = "/propulsion_estimator"
HOVER = [1690, 1690, 1690, 1690, 1000, 1000, 1000, 1000]
VOLTAGE_V = 11.4
# Single bad messages: mixed in at random between the cycles, and each held as a fault in them.
SINGLE_FAULTS = ("nan_voltage", "zero_voltage", "negative_voltage", "disarmed", "too_few_channels", "malformed",
                 "duplicate", "backwards", "future")
FAULTS = SINGLE_FAULTS + ("rc_out_burst", "battery_burst", "rc_out_silence", "battery_silence")


class FaultyRCOut(RCOut):
    """RCOut whose serialized channel count may disagree with the channels that follow it, or whose
    bytes may stop inside the header."""
    announced = None  # channel count written, when not len(channels)
    truncate_to = None  # bytes kept, when set

    def serialize(self, buff):
        if self.announced is None and self.truncate_to is None:
            return super().serialize(buff)
        frame = self.header.frame_id.encode()
        data = struct.pack("<3I", self.header.seq, self.header.stamp.secs, self.header.stamp.nsecs)
        data += struct.pack("<I", len(frame)) + frame
        data += struct.pack("<I%dH" % len(self.channels), self.announced, *self.channels)
        buff.write(data if self.truncate_to is None else data[:self.truncate_to])


def stamp_key(stamp):
    return (stamp.secs, stamp.nsecs)


class SoakTest(unittest.TestCase):
    def setUp(self):
        rospy.init_node("soak")
        p = lambda name: rospy.get_param("~" + name)
        self.duration_s, self.silence_s, self.fault_s = p("duration_s"), p("silence_s"), p("fault_s")
        self.rate_hz, self.battery_rate_hz = p("rc_out_rate_hz"), p("battery_rate_hz")
        self.rate_tolerance, self.rss_growth_limit_kb = p("rate_tolerance"), p("rss_growth_limit_kb")
        self.max_transport_loss, self.max_stall_s = p("max_transport_loss"), p("max_stall_s")
        self.rng = random.Random(p("seed"))
        self.battery_timeout_s = rospy.get_param(NODE + "/battery_timeout_s")
        # A burst of RCOut at three times the load's rate (1200 Hz).
        self.burst_per_tick = 3
        self.min_samples = rospy.get_param(NODE + "/payload/min_samples")
        rc_out_topic = rospy.get_param(NODE + "/rc_out_topic")
        self.rc_out_topic = rc_out_topic

        # Every RCOut through one publisher: one connection keeps their order.
        self.rc_out_pub = rospy.Publisher(rc_out_topic, FaultyRCOut, queue_size=20000)
        self.battery_pub = rospy.Publisher(rospy.get_param(NODE + "/battery_topic"), BatteryState, queue_size=1000)
        # ~totals taken raw: only the stamp is read, so that 400 Hz costs the test little.
        self.answered = collections.Counter()
        self.latest_totals = self.latest_payload = None
        self.statuses = {}  # task -> (receipt time, status)
        # (wall-clock receipt time, the node's CPU seconds then) of each /diagnostics from the node,
        # to find where its process stood still.
        self.diagnostics_s = []
        self.pid = None
        rospy.Subscriber(NODE + "/totals", rospy.AnyMsg, self.on_totals, queue_size=100000, buff_size=1 << 24)
        rospy.Subscriber(NODE + "/payload", rospy.AnyMsg, self.on_payload, queue_size=100000, buff_size=1 << 24)
        rospy.Subscriber("/diagnostics", DiagnosticArray, self.on_diagnostics, queue_size=100)
        rospy.wait_for_service(NODE + "/tare", timeout=60.0)
        wait_until(lambda: self.rc_out_pub.get_num_connections() > 0 and self.battery_pub.get_num_connections() > 0,
                  30.0, "the node subscribing to its inputs")

        self.good, self.bad, self.dont_care = set(), set(), set()  # RCOut stamps sent
        self.last_stamp = rospy.Time.now()  # of the last RCOut sent in order
        self.last_good_stamp = self.last_stamp  # of the last one that must be accepted
        self.last_battery_s = None  # wall time of the last good voltage sent
        self.battery_resumed_s = -1e9
        self.fault = None
        self.phase = "start"  # what the fault-free stretch is, for the report
        self.phase_of = {}  # good RCOut stamp -> fault or phase it was sent in
        self.normal_s, self.normal_sent, self.normal_battery = 0.0, 0, 0  # the fault-free stretches

    # ---- what the node says

    def on_totals(self, message):
        self.answered[struct.unpack_from("<2I", message._buff, 4)] += 1
        self.latest_totals = message._buff

    def on_payload(self, message):
        self.latest_payload = message._buff

    def on_diagnostics(self, message):
        from_node = False
        for status in message.status:
            node, _, task = status.name.partition(": ")
            if node == NODE.lstrip("/"):
                self.statuses[task] = (time.monotonic(), status)
                from_node = True
        if from_node and self.pid is not None:
            self.diagnostics_s.append((time.time(), self.cpu_s(self.pid)))

    @staticmethod
    def cpu_s(pid):
        """User and system CPU seconds the process has used (/proc/PID/stat, fields 14 and 15)."""
        with open("/proc/%d/stat" % pid) as f:
            fields = f.read().rpartition(")")[2].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")

    def stalls(self):
        """(start, end, CPU seconds) of each gap of over three periods between the node's /diagnostics
        in which its process used under a tenth of a core: it stood still, not busy."""
        period = rospy.get_param(NODE + "/diagnostic_period")
        pairs = zip(self.diagnostics_s, self.diagnostics_s[1:])
        return [(a, b, cpu_b - cpu_a) for (a, cpu_a), (b, cpu_b) in pairs
                if b - a > 3.0 * period and cpu_b - cpu_a < 0.1 * (b - a)]

    def status(self, task, since=None):
        entry = self.statuses.get(task)
        if entry is None or (since is not None and entry[0] < since):
            return None
        return entry[1]

    def payload(self):
        return PayloadEstimate().deserialize(self.latest_payload) if self.latest_payload else None

    def totals(self):
        return PropulsionTotals().deserialize(self.latest_totals) if self.latest_totals else None

    def node_pid(self):
        uri = rosgraph.Master("/soak").lookupNode(NODE)
        code, message, pid = xmlrpc.client.ServerProxy(uri).getPid("/soak")
        self.assertEqual(code, 1, message)
        return pid

    @staticmethod
    def rss_kb(pid):
        with open("/proc/%d/status" % pid) as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
        raise AssertionError("no VmRSS for pid %d" % pid)

    # ---- what the test sends

    def next_stamp(self):
        self.last_stamp = max(rospy.Time.now(), self.last_stamp + rospy.Duration(0, 1000))
        return self.last_stamp

    def send_rc_out(self, channels, stamp, expect):
        """expect: "good" (must be answered once), "bad" (never) or None (either)."""
        message = FaultyRCOut(channels=channels)
        message.header.stamp = stamp
        self.rc_out_pub.publish(message)
        {"good": self.good, "bad": self.bad, None: self.dont_care}[expect].add(stamp_key(stamp))
        return message

    def send_good_rc_out(self, now):
        channels = HOVER + [1500] * 8 if self.rng.random() < 0.01 else HOVER  # now and then a 16-channel one
        expect = "good"
        if self.last_battery_s is None or now - self.battery_resumed_s < 0.5:
            expect = None  # the voltage may not have reached the node before this
        else:
            age = now - self.last_battery_s
            if abs(age - self.battery_timeout_s) < 0.5:
                expect = None
            elif age > self.battery_timeout_s:
                expect = "bad"
        stamp = self.next_stamp()
        self.send_rc_out(channels, stamp, expect)
        self.phase_of[stamp_key(stamp)] = self.fault or self.phase
        if expect == "good":
            self.last_good_stamp = stamp

    def send_battery(self, voltage_v, now):
        self.battery_pub.publish(BatteryState(voltage=voltage_v))
        if voltage_v > 0.0:
            if self.last_battery_s is None or now - self.last_battery_s > self.battery_timeout_s:
                self.battery_resumed_s = now
            self.last_battery_s = now

    def send_bad(self, kind):
        """One bad message of a single-message fault kind."""
        if kind == "nan_voltage":
            self.battery_pub.publish(BatteryState(voltage=float("nan")))
        elif kind == "zero_voltage":
            self.battery_pub.publish(BatteryState(voltage=0.0))
        elif kind == "negative_voltage":
            self.battery_pub.publish(BatteryState(voltage=-self.rng.uniform(0.1, 30.0)))
        elif kind == "disarmed":
            self.send_rc_out([self.rng.choice((0, 900, 950))] * 8, self.next_stamp(), "bad")
        elif kind == "too_few_channels":
            self.send_rc_out(HOVER[:self.rng.randrange(4)], self.next_stamp(), "bad")
        elif kind == "malformed":
            message = FaultyRCOut(channels=HOVER[:self.rng.randrange(8)])
            message.header.stamp = self.next_stamp()
            if self.rng.random() < 0.5:
                message.announced = len(message.channels) + self.rng.choice((1, 8, 1000, 2 ** 31))
            else:
                message.announced = len(message.channels)
                message.truncate_to = self.rng.randrange(15)  # inside the header
            self.rc_out_pub.publish(message)
            self.bad.add(stamp_key(message.header.stamp))
        elif kind == "duplicate":
            # Sent again with the stamp of the last accepted one: answered once, by then.
            self.send_rc_out(HOVER, self.last_good_stamp, None)
        elif kind == "backwards":
            # Within clock_jump_reset_s: refused (a larger jump back restarts the windows instead).
            self.send_rc_out(HOVER, self.last_good_stamp - rospy.Duration(self.rng.uniform(0.001, 0.9)), "bad")
        elif kind == "future":
            ahead = self.rng.choice((2.0, 60.0, 86400.0 * 365))
            self.send_rc_out(HOVER, rospy.Time.now() + rospy.Duration(ahead), "bad")
        else:
            raise ValueError(kind)

    def drive(self, until=None, min_s=0.0, max_s=None, what="", mixed_bad_hz=0.0):
        """Sends at the nominal rates, with self.fault applied, for at least min_s and until
        `until()` holds (checked on every tick); fails after max_s."""
        period = 1.0 / self.rate_hz
        start = time.monotonic()
        next_tick = start
        sent = battery = 0
        while True:
            now = time.monotonic()
            elapsed = now - start
            done = until is None or until()  # on every tick: a verdict may come before min_s
            if elapsed >= min_s and done:
                break
            if max_s is not None and elapsed > max_s:
                raise AssertionError("%s: not within %.0f s" % (what, max_s))
            self.tick(now)
            if self.fault is None:
                sent += 1
            if mixed_bad_hz > 0.0 and self.rng.random() < mixed_bad_hz * period:
                self.send_bad(self.rng.choice(SINGLE_FAULTS))
            next_tick += period
            delay = next_tick - time.monotonic()
            if delay > 0:
                time.sleep(delay)
            elif delay < -0.05:
                next_tick = time.monotonic()  # fell behind: no catch-up burst
        if self.fault is None:
            self.normal_s += time.monotonic() - start
            self.normal_sent += sent

    def tick(self, now):
        fault = self.fault
        silent_battery = fault == "battery_silence"
        battery_due = self.last_battery_s is None or now - self.last_battery_s >= 1.0 / self.battery_rate_hz
        if not silent_battery and battery_due:
            self.send_battery(VOLTAGE_V, now)
            if fault is None:
                self.normal_battery += 1
        if fault == "battery_burst":
            self.battery_pub.publish(BatteryState(voltage=VOLTAGE_V))  # a voltage on every tick
        if fault == "rc_out_silence":
            return
        if fault == "disarmed":
            self.send_bad("disarmed")
            return
        self.send_good_rc_out(now)
        if fault == "rc_out_burst":
            for _ in range(self.burst_per_tick - 1):
                self.send_good_rc_out(now)
        elif fault in SINGLE_FAULTS and self.rng.random() < 20.0 / self.rate_hz:
            self.send_bad(fault)

    # ---- faults and their diagnostics

    def named(self, fault, since):
        """Whether a status received since `since` names the fault."""
        outputs, inputs = self.status("Motor outputs", since), self.status("Inputs", since)
        warn = DiagnosticStatus.WARN
        texts = {
            "nan_voltage": (outputs, warn, "battery voltage nan V refused"),
            "zero_voltage": (outputs, warn, "battery voltage 0 V refused"),
            "negative_voltage": (outputs, warn, "battery voltage -"),
            # Disarmed is the normal state on the ground: said plainly, not a warning.
            "disarmed": (outputs, DiagnosticStatus.OK, "at or below disarmed_pwm_max_us"),
            "too_few_channels": (outputs, warn, " channels, motor channel "),
            "malformed": (outputs, DiagnosticStatus.ERROR, "malformed mavros_msgs/RCOut"),
            "duplicate": (outputs, warn, "(a duplicate)"),
            "backwards": (outputs, warn, "stamp went back by"),
            "future": (outputs, warn, "ahead of the receiving clock"),
            "rc_out_silence": (inputs, warn, "no motor outputs on " + self.rc_out_topic),
            "battery_silence": (inputs, DiagnosticStatus.ERROR, "estimates stopped: no battery voltage for"),
        }
        if fault == "battery_burst":
            # Harmless, and not a warning: the Inputs rates show it.
            return inputs is not None and self.value(inputs, "battery rate (Hz)") > 10.0 * self.battery_rate_hz
        if fault == "rc_out_burst":
            # Harmless too (the windows are sized by time, any rate works): the Inputs rate shows it.
            return inputs is not None and self.value(inputs, "rc_out rate (Hz)") > 2.0 * self.rate_hz
        status, level, text = texts[fault]
        return status is not None and status.level == level and text in status.message

    @staticmethod
    def value(status, key):
        return float(next(v.value for v in status.values if v.key == key))

    def cleared(self, since):
        outputs, inputs = self.status("Motor outputs", since), self.status("Inputs", since)
        return (outputs is not None and inputs is not None and outputs.level == DiagnosticStatus.OK
                and outputs.message == "ok" and inputs.level == DiagnosticStatus.OK
                and inputs.message == "receiving"
                and self.value(inputs, "battery rate (Hz)") <= 3.0 * self.battery_rate_hz)

    def describe_counts(self):
        outputs = self.status("Motor outputs")
        if outputs is None:
            return "none"
        return ", ".join("%s %s" % (v.key, v.value) for v in outputs.values if v.value not in ("0", "none"))

    def describe_statuses(self):
        return "; ".join("%s: %d %s" % (task, s.level, s.message) for task, (_, s) in sorted(self.statuses.items()))

    def hold_fault(self, fault):
        """Holds `fault` until a diagnostic names it (and at least fault_s, or silence_s for a
        silence), then sends only good messages until the diagnostics are clear again."""
        length = self.silence_s if fault.endswith("silence") else self.fault_s
        start = time.monotonic()
        self.fault = fault
        named_after_s = []

        def named_once():
            if not named_after_s and self.named(fault, start):
                named_after_s.append(time.monotonic() - start)
            return bool(named_after_s)
        self.drive(until=named_once, min_s=length, max_s=length + 30.0,
                   what="%s named by /diagnostics (%s)" % (fault, self.describe_statuses()))
        self.fault = None
        self.phase = "after " + fault
        end = time.monotonic()
        self.drive(until=lambda: self.cleared(end + 0.5), max_s=30.0,
                   what="diagnostics clear after %s (%s)" % (fault, self.describe_statuses()))
        rospy.loginfo("soak: %s held %.1f s, named after %.1f s, cleared after %.1f s", fault, end - start,
                      named_after_s[0], time.monotonic() - end)

    def hover_estimate(self, what):
        """Hovers until the payload estimate is over at least min_samples hover samples."""
        def ready():
            payload = self.payload()
            return payload is not None and payload.state == "hovering" and payload.window_samples >= self.min_samples
        self.drive(until=ready, min_s=3.0, max_s=60.0, what=what)
        payload, totals = self.payload(), self.totals()
        return totals.mass_kg, payload.total_mass_kg, payload.payload_mass_kg, payload.empty_mass_source

    # ---- the test

    def test_soak(self):
        pid = self.pid = self.node_pid()
        before = self.hover_estimate("a first hover")
        rss_early = self.rss_kb(pid)
        rospy.loginfo("soak: node pid %d, VmRSS %d kB after the first hover; estimate %s", pid, rss_early, before)
        start = time.monotonic()
        cycles, rss_after_cycle = 0, []
        while cycles == 0 or time.monotonic() - start < self.duration_s:
            faults = list(FAULTS)
            self.rng.shuffle(faults)
            for fault in faults:
                self.hold_fault(fault)
            self.phase = "mixed"
            self.drive(min_s=10.0, mixed_bad_hz=20.0)
            self.phase = "after mixed"
            cycles += 1
            rss_after_cycle.append(self.rss_kb(pid))
            rospy.loginfo("soak: cycle %d done after %.0f s, VmRSS %d kB", cycles, time.monotonic() - start,
                          rss_after_cycle[-1])
        after = self.hover_estimate("a hover after the faults")
        rss_end = self.rss_kb(pid)
        time.sleep(3.0)  # the last answers on their way
        # The node's count of accepted RCOut, from a status sent after the last of them.
        counted_since = time.monotonic()
        wait_until(lambda: self.status("Motor outputs", counted_since) is not None, 10.0,
                   "a Motor outputs status after the last RCOut")
        accepted = int(self.value(self.status("Motor outputs", counted_since), "accepted"))

        self.assertEqual(self.node_pid(), pid, "the node was restarted")
        missing = self.good - set(self.answered)
        answered_bad = self.bad & set(self.answered)
        twice = [k for k, n in self.answered.items() if n > 1]
        rospy.loginfo("soak: %d cycles; %d good RCOut sent, %d bad, %d either; %d answers; VmRSS %d -> %s -> %d kB",
                      cycles, len(self.good), len(self.bad), len(self.dont_care), sum(self.answered.values()),
                      rss_early, rss_after_cycle, rss_end)
        # Sent while the node's process stood still, or in the second after, while it reads the backlog:
        # refused as stale once it runs again (see above).
        stalls = self.stalls()
        stalled_s = sum(b - a for a, b, _ in stalls)
        in_stall = {k for k in missing if any(a <= k[0] + 1e-9 * k[1] <= b + 1.0 for a, b, _ in stalls)}
        # Answers the node published (one per message it accepted) that never reached this test.
        lost = accepted - sum(self.answered.values())
        rospy.loginfo("soak: the node accepted %d RCOut; %d answers lost on the way to this test; %d good RCOut "
                      "unanswered were sent in %d stalls of the node (%.1f s; start, end, CPU s: %s); its counts: %s",
                      accepted, lost, len(in_stall), len(stalls), stalled_s, stalls, self.describe_counts())
        unexplained = missing - in_stall
        self.assertLessEqual(len(unexplained), max(lost, 0),
                             "%d of %d good RCOut messages never answered (%s), neither counted accepted by the node "
                             "(%d answers lost in transport) nor sent while it stood still (%d stalls, %.1f s); the "
                             "node's count: %s" %
                             (len(unexplained), len(self.good),
                              collections.Counter(self.phase_of[k] for k in unexplained), lost, len(stalls), stalled_s,
                              self.describe_counts()))
        self.assertLessEqual(stalled_s, self.max_stall_s, "the node stood still %.1f s in all: %s" % (stalled_s, stalls))
        self.assertLessEqual(lost, self.max_transport_loss * accepted, "%d of %d answers lost in transport (%s)" %
                             (lost, accepted, collections.Counter(self.phase_of[k] for k in missing)))
        self.assertEqual(answered_bad, set(), "bad RCOut messages answered")
        self.assertEqual(twice, [], "RCOut messages answered more than once")
        unknown = set(self.answered) - self.good - self.dont_care
        self.assertEqual(unknown, set(), "answers to stamps never sent as good")

        self.assertEqual(after[3], before[3])
        for name, b, a in zip(("~totals mass_kg", "~payload total_mass_kg", "~payload payload_mass_kg"), before, after):
            self.assertAlmostEqual(a, b, delta=1e-9, msg="%s after the faults %r, before %r" % (name, a, b))
        self.assertLessEqual(rss_end - rss_early, self.rss_growth_limit_kb, "VmRSS grew from %d to %d kB" %
                             (rss_early, rss_end))
        if len(rss_after_cycle) > 1:
            self.assertLessEqual(rss_end - rss_after_cycle[0], self.rss_growth_limit_kb,
                                 "VmRSS grew after the first cycle: %s" % rss_after_cycle)

        # The load claimed is the load applied: rates in the fault-free stretches.
        rate = self.normal_sent / self.normal_s
        battery_rate = self.normal_battery / self.normal_s
        rospy.loginfo("soak: fault-free stretches %.0f s: RCOut %.1f Hz, battery %.2f Hz", self.normal_s, rate,
                      battery_rate)
        self.assertGreaterEqual(rate, self.rate_hz * (1.0 - self.rate_tolerance), "RCOut rate not achieved")
        self.assertGreaterEqual(battery_rate, self.battery_rate_hz * (1.0 - self.rate_tolerance) - 1.0 / self.normal_s,
                                "battery rate not achieved")


if __name__ == "__main__":
    rostest.rosrun("propulsion_estimator", "soak", SoakTest)
