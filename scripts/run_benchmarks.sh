#!/bin/sh
# Runs every google-benchmark binary of the build (bench_*; built only when libbenchmark-dev is
# installed). Usage: scripts/run_benchmarks.sh [DIR] (default: the colcon build's devel space).
set -eu
dir="${1:-$(dirname "$0")/../.ws/build/propulsion_estimator/devel/lib/propulsion_estimator}"
found=0
for bench in "$dir"/bench_*; do
  [ -x "$bench" ] || continue
  found=1
  echo "== $(basename "$bench")"
  "$bench"
done
if [ "$found" -eq 0 ]; then
  echo "run_benchmarks.sh: no bench_* executables in $dir (install libbenchmark-dev, then make build)" >&2
  exit 1
fi
