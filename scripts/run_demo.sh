#!/bin/bash
# The README's main job: replays the bundled flight bag (empty hover, then the thesis' 294 g and
# 396 g payloads on a cable) through estimator_node and prints the payload estimates beside the
# weighed masses. roslaunch starts a ROS master when none runs. A replay that has not ended after
# five minutes (about 30 s expected) is stopped and its output shown, so that a hang fails with
# its reason rather than holding a CI run until its own limit.
set -eu
export PATH=/usr/bin:$PATH
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "Replaying the bundled flight through estimator_node at 4x (about 30 s)."
echo "Watch it from another shell: rostopic echo /propulsion_estimator/payload (or /totals, /motors)."
status=0
timeout --signal=INT --kill-after=30 300 roslaunch propulsion_estimator demo.launch table_file:="$work/table.txt" "$@" \
  >"$work/launch.log" 2>&1 || status=$?
if [ "$status" -ne 0 ] || [ ! -s "$work/table.txt" ]; then
  cat "$work/launch.log"
  if [ "$status" -eq 124 ]; then
    echo "run_demo.sh: the replay had not ended after 300 s and was stopped (roslaunch output above)" >&2
  else
    echo "run_demo.sh: the replay did not produce a report (roslaunch output above)" >&2
  fi
  exit 1
fi
echo
cat "$work/table.txt"
grep -q "^All payload estimates within" "$work/table.txt"
