#!/bin/sh
# Installs what cross-building the ROS-free modules and their unit tests for arm64 (Raspberry Pi)
# and running them under qemu-user needs (make arm64): Debian 12's cross compiler, the arm64
# multiarch -dev packages of the libraries, qemu-aarch64. ROS itself is not co-installable for
# arm64, so the node is not cross-built. Does nothing when everything is already installed.
set -eu

# libyaml-cpp-dev is not Multi-Arch: same (installing the arm64 one removes the host one, which the
# ROS build needs): the host's headers serve both, the arm64 runtime library is linked through
# cmake/aarch64-linux-gnu/yaml-cpp-config.cmake.
PACKAGES="
  cmake make crossbuild-essential-arm64 qemu-user
  libeigen3-dev libyaml-cpp-dev libyaml-cpp0.7:arm64 liburdfdom-dev:arm64 libcsv-dev:arm64
  libgtest-dev:arm64 libbenchmark-dev:arm64
"

missing=""
for package in $PACKAGES; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing="$missing $package"
done
[ -z "$missing" ] && exit 0

echo "Installing:$missing"
if [ "$(id -u)" -ne 0 ]; then
  echo "install_arm64_deps.sh: installing packages needs root (run as root or with sudo)" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
dpkg --print-foreign-architectures | grep -qx arm64 || dpkg --add-architecture arm64
apt-get update -q
# --no-remove: never trade a host package for an arm64 one.
# shellcheck disable=SC2086
apt-get install -y -q --no-install-recommends --no-remove $missing
