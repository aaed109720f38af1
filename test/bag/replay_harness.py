"""One simulated flight bag played once, on simulated time, through several estimator_nodes at the
same time, each with its own model: what the bag replay rostests share (test_replay_effects.py,
test_diagnose_then_replay.py; test_replay_payload.py plays through the launch file's node). Each node is tared in the manifest's empty segment; the result is,
per node, the SegmentReport of its ~payload estimates and its last "Effects" diagnostic."""
import os
import signal
import subprocess
import sys
import time

import rosbag
import roslaunch
import rospkg
import rospy
from diagnostic_msgs.msg import DiagnosticArray
from propulsion_estimator.msg import PayloadEstimate
from std_srvs.srv import Trigger

sys.path.insert(0, os.path.join(rospkg.RosPack().get_path("propulsion_estimator"), "scripts"))
from payload_report import SegmentReport, load_segments  # noqa: E402


def replay(bag_path, manifest, models, urdf, rate):
    """Plays `bag_path` through one estimator_node per entry of `models` ({node name: model file}),
    all with `urdf`; returns ({name: SegmentReport}, {name: last Effects DiagnosticStatus}, the
    player's exit status)."""
    _, segments = load_segments(manifest)
    with rosbag.Bag(bag_path) as bag:
        start = bag.get_start_time()
    reports = {name: SegmentReport(segments, start, tare_segment=0) for name in models}
    effects_status = {}

    def on_diagnostics(message):
        for status in message.status:
            for name in models:
                if name in status.name and status.name.endswith(": Effects"):
                    effects_status[name] = status

    launch = roslaunch.scriptapi.ROSLaunch()
    launch.start()
    processes = []
    for name, model in models.items():
        rospy.set_param("/%s/model" % name, model)
        rospy.set_param("/%s/urdf_file" % name, urdf)
        processes.append(launch.launch(roslaunch.core.Node("propulsion_estimator", "estimator_node", name=name,
                                                           namespace="/", output="log")))
        rospy.Subscriber("/%s/payload" % name, PayloadEstimate, reports[name].on_payload)
    rospy.Subscriber("/diagnostics", DiagnosticArray, on_diagnostics)
    tares = {}
    for name in models:
        rospy.wait_for_service("/%s/tare" % name, timeout=30.0)
        tares[name] = rospy.ServiceProxy("/%s/tare" % name, Trigger)

    try:
        status = play(bag_path, rate, [(reports[name], tares[name]) for name in models])
    finally:
        for process in processes:
            process.stop()
        launch.stop()
    return reports, effects_status, status


def play(bag_path, rate, tared_reports):
    """Plays `bag_path` on simulated time at `rate`, calling each (SegmentReport, ~tare proxy) pair's
    ~tare once its report says it is due; returns the player's exit status."""
    # Its own process group: `rosbag play` runs the player in a child process that must stop too.
    player = subprocess.Popen(["rosbag", "play", "--clock", "--quiet", "--delay=1", "--rate=%s" % rate, bag_path],
                              start_new_session=True)
    try:
        while player.poll() is None:
            for report, tare in tared_reports:
                if report.tare_due(rospy.Time.now().to_sec()):
                    answer = tare()
                    report.tared = answer.success
                    report.tare_answer = answer.message
            time.sleep(0.1)  # wall time: simulated time stops with the bag
    finally:
        if player.poll() is None:
            os.killpg(player.pid, signal.SIGTERM)
            player.wait()
    return player.returncode
