#!/usr/bin/env python3
"""Payload estimates of a replayed flight beside the true masses of its manifest.

Runs as a node next to estimator_node while a flight bag plays on simulated time: calls ~tare
during the manifest's empty segment, then prints, for every segment, the estimated total and
payload mass beside the weighed ones. The bag replay test imports SegmentReport from here.

Parameters: ~manifest (path), ~flight (index in the manifest, default 0), ~estimator (node
name, default /propulsion_estimator), ~tare_segment (index, default 0), ~tolerance_kg
(optional: adds a verdict line on the payload errors), ~table_file (optional: the printed
table), ~results_file (optional: the rows as YAML)."""
import math
import os
import sys

import yaml


def load_segments(manifest_path, flight_index=0):
    """(bag path, segments) of one flight; times stay relative to the bag's first message."""
    with open(manifest_path) as f:
        manifest = yaml.safe_load(f)
    flight = manifest["flights"][flight_index]
    bag = os.path.join(os.path.dirname(os.path.abspath(manifest_path)), flight.get("log", flight.get("bag")))
    return bag, [dict(start=float(s["start"]), end=float(s["end"]), mass_kg=float(s["mass_kg"]))
                 for s in flight["segments"]]


class SegmentReport:
    """Collects ~payload messages and tells, per segment, what the estimator concluded."""

    def __init__(self, segments, bag_start_s, tare_segment=0):
        self.segments = segments
        self.bag_start_s = bag_start_s
        self.tare_segment = tare_segment
        self.tared = False
        self.tare_answer = None
        self._last_hovering = [None] * len(segments)

    def absolute(self, segment, key):
        return self.bag_start_s + segment[key]

    def on_payload(self, message):
        stamp = message.header.stamp.to_sec()
        for i, segment in enumerate(self.segments):
            if self.absolute(segment, "start") <= stamp <= self.absolute(segment, "end") and message.hovering:
                self._last_hovering[i] = message

    def tare_due(self, now_s):
        """Tare in the last third of the empty segment, once the hover average has settled."""
        segment = self.segments[self.tare_segment]
        start, end = self.absolute(segment, "start"), self.absolute(segment, "end")
        return not self.tared and start + 2.0 / 3.0 * (end - start) <= now_s <= end

    def finished(self, now_s):
        return now_s > self.absolute(self.segments[-1], "end") + 0.5

    def rows(self):
        empty_kg = self.segments[self.tare_segment]["mass_kg"]
        rows = []
        for i, segment in enumerate(self.segments):
            message = self._last_hovering[i]
            nan = float("nan")
            rows.append(dict(
                segment=i,
                true_total_kg=segment["mass_kg"],
                true_payload_kg=segment["mass_kg"] - empty_kg,
                total_kg=message.total_mass_kg if message else nan,
                payload_kg=message.payload_mass_kg if message else nan,
                std_kg=message.mass_std_kg if message else nan,
                samples=message.window_samples if message else 0,
                state=message.state if message else "never hovering"))
        return rows

    def verdict(self, tolerance_kg):
        """(ok, sentence): whether every segment's payload estimate lies within tolerance_kg."""
        if not self.tared:
            return False, "No successful ~tare in segment %d: %s" % (self.tare_segment, self.tare_answer)
        for r in self.rows():
            error = abs(r["payload_kg"] - r["true_payload_kg"])
            if not error <= tolerance_kg:  # NaN fails too
                return False, "Segment %d: payload estimate %.3f kg, weighed %.3f kg: off by more than %.3f kg." % (
                    r["segment"], r["payload_kg"], r["true_payload_kg"], tolerance_kg)
        return True, "All payload estimates within %.3f kg of the weighed masses." % tolerance_kg

    def table(self):
        lines = ["segment  true total  est. total   true payload  est. payload   error    std   samples",
                 "         (kg)        (kg)         (kg)          (kg)           (%)      (kg)"]
        for r in self.rows():
            error = (100.0 * (r["payload_kg"] - r["true_payload_kg"]) / r["true_payload_kg"]
                     if r["true_payload_kg"] > 0 and not math.isnan(r["payload_kg"]) else float("nan"))
            lines.append("%7d  %10.3f  %10.3f   %12.3f  %12.3f  %7.1f  %6.3f  %7d%s" % (
                r["segment"], r["true_total_kg"], r["total_kg"], r["true_payload_kg"], r["payload_kg"], error,
                r["std_kg"], r["samples"], "   (tare)" if r["segment"] == self.tare_segment else ""))
        return "\n".join(lines)


def main():
    # A node's settings are parameters: --help says so instead of waiting for a ROS master.
    if "-h" in sys.argv[1:] or "--help" in sys.argv[1:]:
        print(__doc__)
        return 0
    import rosbag
    import rospy
    from propulsion_estimator.msg import PayloadEstimate
    from std_srvs.srv import Trigger

    rospy.init_node("payload_report")
    bag_path, segments = load_segments(rospy.get_param("~manifest"), rospy.get_param("~flight", 0))
    with rosbag.Bag(bag_path) as bag:
        bag_start = bag.get_start_time()
    estimator = rospy.get_param("~estimator", "/propulsion_estimator")
    report = SegmentReport(segments, bag_start, rospy.get_param("~tare_segment", 0))
    rospy.Subscriber(estimator + "/payload", PayloadEstimate, report.on_payload)
    tare = rospy.ServiceProxy(estimator + "/tare", Trigger)
    rospy.wait_for_service(estimator + "/tare")
    rospy.loginfo("replaying %s: %d segments, tare during segment %d", bag_path, len(segments), report.tare_segment)
    rate = rospy.Rate(10.0)
    while not rospy.is_shutdown() and not report.finished(rospy.Time.now().to_sec()):
        if report.tare_due(rospy.Time.now().to_sec()):
            answer = tare()
            report.tared = answer.success
            report.tare_answer = answer.message
            rospy.loginfo("~tare: %s", answer.message)
        rate.sleep()
    text = "Payload estimates of %s (~tare: %s)\n%s\n" % (os.path.basename(bag_path), report.tare_answer,
                                                         report.table())
    if rospy.has_param("~tolerance_kg"):
        text += report.verdict(rospy.get_param("~tolerance_kg"))[1] + "\n"
    print("\n" + text, flush=True)
    table_file = rospy.get_param("~table_file", "")
    if table_file:
        with open(table_file, "w") as f:
            f.write(text)
    results_file = rospy.get_param("~results_file", "")
    if results_file:
        with open(results_file, "w") as f:
            yaml.safe_dump({"tare": report.tare_answer, "segments": report.rows()}, f)
    rospy.signal_shutdown("report done")


if __name__ == "__main__":
    main()
