#!/bin/sh
# Times diagnose_gap's reading of an hour of flight: two simulated 30-minute flights, rc/out at
# 50 Hz and every MAVROS topic at its rate (the bags also hold /sim/truth, which is not read),
# read with --jobs 1 and --jobs 2 (the figures need Debian's python3 with matplotlib). The bags
# are simulated once and kept in the cache directory.
# Usage: scripts/bench_diagnose_gap.sh [CACHE_DIR [JSON]] (default /tmp/pe_bench_diagnose_gap), after
# `make build` and `source .ws/install/setup.sh` (diagnose_gap and simulate on the ROS path); with
# JSON, also writes the figures there for scripts/write_benchmarks.py (make bench).
set -eu
repo="$(cd "$(dirname "$0")/.." && pwd)"
cache="${1:-/tmp/pe_bench_diagnose_gap}"
json="${2:-}"
mkdir -p "$cache"

if [ ! -f "$cache/flights.yaml" ]; then
  "$repo/scripts/write_hour_flight.sh" "$cache" 50
  echo "flights:" >"$cache/flights.yaml.part"
  for seed in 1 2; do
    rosrun propulsion_estimator simulate flight --params "$cache/params.yaml" --profile "$cache/profile.yaml" \
      --seed "$seed" --bag "$cache/flight_$seed.bag" --manifest "$cache/flight_$seed.yaml"
    sed '1,/^flights:/d' "$cache/flight_$seed.yaml" >>"$cache/flights.yaml.part"
  done
  mv "$cache/flights.yaml.part" "$cache/flights.yaml"
fi

messages=$(rosbag info "$cache"/flight_*.bag | awk '/^messages:/ { total += $2 } END { print total }')
echo "bags: $(du -ch "$cache"/flight_*.bag | tail -1 | cut -f1), $messages messages (/sim/truth included)"
runs=""
for jobs in 1 2; do
  start=$(date +%s.%N)
  # GNU time's %M: the peak resident memory in kB.
  /usr/bin/time -f '%M' -o "$cache/peak_kb_$jobs.txt" \
    rosrun propulsion_estimator diagnose_gap --model "$repo/config/e300_dji2212_dji9443.yaml" \
    --urdf "$repo/config/f450_quad.urdf" --manifest "$cache/flights.yaml" --out "$cache/report_$jobs" \
    --jobs "$jobs" --python /usr/bin/python3 >"$cache/run_$jobs.txt"
  end=$(date +%s.%N)
  whole=$(awk "BEGIN { printf \"%.2f\", $end - $start }")
  grep '^read [0-9]' "$cache/run_$jobs.txt"
  echo "  whole run (reading, diagnosis, report, figures): $whole s, peak memory $(cat "$cache/peak_kb_$jobs.txt") kB"
  reading=$(sed -n 's/^read [0-9].* in \([0-9.]*\) s with.*/\1/p' "$cache/run_$jobs.txt")
  runs="$runs${runs:+, }{\"jobs\": $jobs, \"reading_s\": $reading, \"whole_s\": $whole, \"peak_kb\": $(cat "$cache/peak_kb_$jobs.txt")}"
done
if [ -n "$json" ]; then
  echo "{\"bags_mb\": $(du -cm "$cache"/flight_*.bag | tail -1 | cut -f1), \"messages\": $messages, \"runs\": [$runs]}" >"$json"
fi
