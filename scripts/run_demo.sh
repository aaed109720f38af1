#!/bin/bash
# The README's main job: replays the bundled flight bag through estimator_node (roslaunch starts a
# ROS master if none runs) and prints the payload estimates beside the weighed masses.
set -eu
export PATH=/usr/bin:$PATH
exec roslaunch propulsion_estimator demo.launch "$@"
