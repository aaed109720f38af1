#!/bin/sh
# Times fleet (docs/fleet.md) on a simulated fleet: 10 vehicles of 20 flights each (200 logs of about
# 70 s, PX4 ULog; scripts/simulate_fleet.py), simulated once and kept in the cache directory. A
# first run learns the vehicles' references (diagnose_gap, kept beside the database); the timed run
# then estimates every log into a fresh database with --jobs 2 and writes the report. Its CPU time
# (fleet and every estimate it runs) gives the flight-hours processed per core-second, and from
# it the time 1,000 flight-hours take on 16 cores.
# Usage: scripts/bench_fleet.sh BIN_DIR [CACHE_DIR [JSON]] (BIN_DIR: the build's devel/lib/propulsion_estimator)
set -eu
repo="$(cd "$(dirname "$0")/.." && pwd)"
bin="$1"
cache="${2:-/tmp/pe_bench_fleet}"
json="${3:-}"
if [ ! -f "$cache/fleet.yaml" ]; then
  /usr/bin/python3 "$repo/scripts/simulate_fleet.py" --bin "$bin" --repo "$repo" --out "$cache" --vehicles 10 \
    --flights 20 --seed 4242 --jobs 2
fi
fleet() {
  /usr/bin/python3 "$repo/scripts/fleet.py" "$@" --estimate "$bin/estimate" --diagnose-gap "$bin/diagnose_gap" --quiet
}
# The references, learned once (the timed run finds them kept).
fleet "$cache/fleet.yaml" --jobs 2 --no-report >/dev/null
sed -e 's/^vehicle_pattern:/database: timed.sqlite\nreport: timed_report\nvehicle_pattern:/' "$cache/fleet.yaml" \
  >"$cache/timed.yaml"
rm -rf "$cache/timed.sqlite" "$cache/timed.sqlite-wal" "$cache/timed.sqlite-shm" "$cache/timed_report"
# GNU time: wall seconds, and the CPU seconds of fleet and the estimate processes it waited for.
/usr/bin/time -f '%e %U %S %M' -o "$cache/time.txt" /usr/bin/python3 "$repo/scripts/fleet.py" "$cache/timed.yaml" \
  --jobs 2 --estimate "$bin/estimate" --diagnose-gap "$bin/diagnose_gap" --quiet >"$cache/run.txt"
hours=$(/usr/bin/python3 -c "
import sqlite3
print(sqlite3.connect('$cache/timed.sqlite').execute('SELECT SUM(duration_s) / 3600.0 FROM flights').fetchone()[0])")
flights=$(/usr/bin/python3 -c "
import sqlite3
print(sqlite3.connect('$cache/timed.sqlite').execute('SELECT COUNT(*) FROM flights').fetchone()[0])")
awk -v hours="$hours" -v flights="$flights" '{
  cpu = $2 + $3; rate = hours / cpu
  printf "fleet: %d flights, %.2f flight-hours in %.1f s (jobs 2), %.1f s of CPU: %.4f flight-hours per core-second; ", flights, hours, $1, cpu, rate
  printf "1,000 flight-hours on 16 cores: %.1f min\n", 1000 / rate / 16 / 60 }' "$cache/time.txt"
if [ -n "$json" ]; then
  awk -v hours="$hours" -v flights="$flights" '{ cpu = $2 + $3
    printf "{\"flights\": %d, \"flight_hours\": %.4f, \"wall_s\": %.2f, \"cpu_s\": %.2f, \"peak_kb\": %d, \"hours_per_core_s\": %.6f, \"minutes_1000h_16_cores\": %.2f}\n",
      flights, hours, $1, cpu, $4, hours / cpu, 1000 / (hours / cpu) / 16 / 60 }' "$cache/time.txt" >"$json"
fi
