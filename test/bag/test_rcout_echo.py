#!/usr/bin/env python3
"""`rostopic echo /mavros/rc/out` during `rosbag play` of a simulated flight shows the channels.

Debian has no mavros_msgs, so rostopic cannot load the RCOut class on this machine. The test
stands in for an installed mavros_msgs with a class that genpy generates at test time, in a
temporary directory, from the definition stored in the bag itself; rostopic then subscribes with
that class's md5sum, which the publisher (rosbag play) must match."""
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import unittest

import rosbag
import rospkg
import rostest

BAG = os.path.join(rospkg.RosPack().get_path("propulsion_estimator"), "config", "demo", "demo_flight.bag")


def mavros_msgs_stand_in(definition):
    """A directory holding a `mavros_msgs.msg` module whose RCOut genpy builds from `definition`."""
    root = tempfile.mkdtemp(prefix="pe_mavros_msgs_")
    os.makedirs(os.path.join(root, "mavros_msgs", "msg"))
    open(os.path.join(root, "mavros_msgs", "__init__.py"), "w").close()
    with open(os.path.join(root, "mavros_msgs", "msg", "__init__.py"), "w") as f:
        f.write("import genpy.dynamic\nRCOut = genpy.dynamic.generate_dynamic('mavros_msgs/RCOut', %r)"
                "['mavros_msgs/RCOut']\n" % definition)
    return root


class RcOutEchoTest(unittest.TestCase):
    def test_rostopic_echo_shows_the_channels(self):
        with rosbag.Bag(BAG) as bag:
            connection = next(c for c in bag._get_connections() if c.topic == "/mavros/rc/out")
        self.assertEqual(connection.datatype, "mavros_msgs/RCOut")
        self.assertEqual(connection.md5sum, "52cacf104bab5ae3b103cfe176590713")
        environment = dict(os.environ)
        stand_in = mavros_msgs_stand_in(connection.msg_def)
        self.addCleanup(shutil.rmtree, stand_in, True)
        environment["PYTHONPATH"] = stand_in + os.pathsep + environment.get("PYTHONPATH", "")
        # Skip the first seconds of the flight, where the vehicle is still disarmed on the ground.
        # Its own process group: `rosbag play` runs the player in a child process that must stop too.
        player = subprocess.Popen(["rosbag", "play", "--quiet", "--start=10", BAG], stdout=subprocess.DEVNULL,
                                  start_new_session=True)
        try:
            echo = subprocess.run(["rostopic", "echo", "-n", "3", "/mavros/rc/out"], env=environment,
                                  capture_output=True, text=True, timeout=60)
        finally:
            os.killpg(player.pid, signal.SIGTERM)
            player.wait()
        self.assertEqual(echo.returncode, 0, echo.stderr)
        channel_lines = [line for line in echo.stdout.splitlines() if line.startswith("channels: [")]
        self.assertEqual(len(channel_lines), 3, echo.stdout)
        channels = [int(value) for value in channel_lines[0][len("channels: ["):-1].split(",")]
        self.assertEqual(len(channels), 8)
        for pwm in channels[:4]:  # hovering motors of the PX4 quad (PWM_MAIN 1100..1950 us)
            self.assertGreater(pwm, 1100)
            self.assertLess(pwm, 1950)
        sys.stdout.write(channel_lines[0] + "\n")


if __name__ == "__main__":
    rostest.rosrun("propulsion_estimator", "rcout_echo", RcOutEchoTest)
