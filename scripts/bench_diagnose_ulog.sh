#!/bin/sh
# Times diagnose_gap, then estimate, on an hour of PX4 ULog at PX4's default logging rates or faster: two simulated
# 30-minute flights (scripts/write_hour_flight.sh, actuator_outputs at 10 Hz,
# sensor_combined and vehicle_attitude at 200 Hz; see test/benchmark/px4_hour_ulog.cpp), written
# once and kept in the cache directory, diagnosed whole (reading, diagnosis, report, figures), and
# estimated on one core (reading, the onboard session, estimates.csv and summary.md; no figure).
# Usage: scripts/bench_diagnose_ulog.sh BIN_DIR [CACHE_DIR [JSON]] (BIN_DIR holds px4_hour_ulog,
# diagnose_gap and estimate: the build's devel/lib/propulsion_estimator; default cache /tmp/pe_bench_diagnose_ulog),
# after `make build`; with JSON, also writes the figures there.
set -eu
repo="$(cd "$(dirname "$0")/.." && pwd)"
bin="$1"
cache="${2:-/tmp/pe_bench_diagnose_ulog}"
json="${3:-}"
mkdir -p "$cache"

if [ ! -f "$cache/flights.yaml" ]; then
  "$repo/scripts/write_hour_flight.sh" "$cache" 10
  "$bin/px4_hour_ulog" "$cache/params.yaml" "$cache/profile.yaml" "$cache"
fi

echo "ULogs: $(du -ch "$cache"/flight_*.ulg | tail -1 | cut -f1)"
start=$(date +%s.%N)
# GNU time: peak resident memory in kB, and the CPU seconds of the run and its plotting child.
/usr/bin/time -f '%M %U %S' -o "$cache/time.txt" \
  "$bin/diagnose_gap" --model "$repo/config/e300_dji2212_dji9443.yaml" \
  --urdf "$repo/config/f450_quad.urdf" --manifest "$cache/flights.yaml" --out "$cache/report" \
  --python /usr/bin/python3 >"$cache/run.txt"
end=$(date +%s.%N)
whole=$(awk "BEGIN { printf \"%.2f\", $end - $start }")
grep '^read [0-9]' "$cache/run.txt"
peak=$(awk '{ print $1 }' "$cache/time.txt")
cpu=$(awk '{ printf "%.2f", $2 + $3 }' "$cache/time.txt")
echo "  whole run (reading, diagnosis, report, figures): $whole s ($cpu s of CPU), peak memory $peak kB"
reading=$(sed -n 's/^read [0-9].* in \([0-9.]*\) s with.*/\1/p' "$cache/run.txt")

# estimate on one core (taskset), the two logs one after the other.
start=$(date +%s.%N)
/usr/bin/time -f '%M %U %S' -o "$cache/estimate_time.txt" \
  taskset -c 0 "$bin/estimate" --model "$repo/config/e300_dji2212_dji9443.yaml" --urdf "$repo/config/f450_quad.urdf" \
  --out "$cache/estimate" --no-figures --jobs 1 "$cache"/flight_*.ulg >"$cache/estimate_run.txt"
end=$(date +%s.%N)
estimate_whole=$(awk "BEGIN { printf \"%.2f\", $end - $start }")
estimate_peak=$(awk '{ print $1 }' "$cache/estimate_time.txt")
estimate_cpu=$(awk '{ printf "%.2f", $2 + $3 }' "$cache/estimate_time.txt")
echo "  estimate on one core (reading, session, table and summary): $estimate_whole s ($estimate_cpu s of CPU), peak memory $estimate_peak kB"
if [ -n "$json" ]; then
  echo "{\"ulogs_mb\": $(du -cm "$cache"/flight_*.ulg | tail -1 | cut -f1), \"reading_s\": $reading, \"whole_s\": $whole, \"cpu_s\": $cpu, \"peak_kb\": $peak, \"estimate_s\": $estimate_whole, \"estimate_cpu_s\": $estimate_cpu, \"estimate_peak_kb\": $estimate_peak}" >"$json"
fi
