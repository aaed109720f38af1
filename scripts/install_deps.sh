#!/bin/sh
# Installs what building, running and testing the package needs, from Debian 12's own packages
# (ROS 1 lives in /usr there); python3-numpy, valgrind and time are make bench's (the rospy peer,
# the instructions per message, diagnose_gap's peak memory); doxygen is make docs'. Does nothing when everything is
# already installed. python3-pytest and python3-distributed (Dask) are fleet's tests' and its
# --scheduler's.
# `install_deps.sh fuzz` adds clang and its libFuzzer runtime, which only `make fuzz` needs.
set -eu

PACKAGES="
  build-essential cmake pkg-config
  catkin colcon python3-colcon-ros python3-colcon-cmake python3-colcon-test-result
  libroscpp-dev ros-message-generation ros-message-runtime ros-std-msgs libstd-msgs-dev
  ros-sensor-msgs libsensor-msgs-dev ros-geometry-msgs libgeometry-msgs-dev
  ros-std-srvs libstd-srvs-dev ros-diagnostic-msgs libdiagnostic-msgs-dev libdiagnostic-updater-dev
  libtopic-tools-dev librosbag-dev librostest-dev
  rosout rosbash python3-rosbag python3-roslaunch python3-rosmaster python3-rostopic python3-rosnode
  python3-rosservice python3-rosparam python3-rosmsg python3-rostest python3-rospy python3-rosunit
  liburdfdom-dev libtinyxml-dev libeigen3-dev libyaml-cpp-dev libcli11-dev libcsv-dev libgtest-dev libbenchmark-dev
  python3-std-msgs python3-sensor-msgs python3-geometry-msgs python3-diagnostic-msgs python3-std-srvs
  python3-topic-tools python3-matplotlib python3-yaml
  python3-numpy valgrind time doxygen
  python3-pytest python3-distributed
"
if [ "${1:-}" = fuzz ]; then
  PACKAGES="$PACKAGES clang libclang-rt-14-dev"
fi

missing=""
for package in $PACKAGES; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing="$missing $package"
done
[ -z "$missing" ] && exit 0

echo "Installing:$missing"
if [ "$(id -u)" -ne 0 ]; then
  echo "install_deps.sh: installing packages needs root (run as root or with sudo)" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -q
# shellcheck disable=SC2086
apt-get install -y -q --no-install-recommends $missing
