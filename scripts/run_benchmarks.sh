#!/bin/bash
# make bench: runs every benchmark and rewrites docs/BENCHMARKS.md from their figures
# (scripts/write_benchmarks.py), with the machine, the date and the command of each section.
#   1. google benchmark: bench_estimator, bench_rcout_decode, bench_fit, bench_simulate (JSON);
#   2. end to end (scripts/bench_node.py): RCOut at 400 Hz and the battery at 1 Hz for
#      BENCH_DURATION_S seconds (default 60), BENCH_ROUNDS times (default 2), to estimator_node (at
#      its default publishing rate, then publishing every message), the two transport floors and the
#      rospy peer;
#   3. callgrind: estimator_node's instructions per RCOut message, over BENCH_CALLGRIND_MESSAGES
#      (default 2000) at 100 Hz after a 15 s warm-up;
#   4. scripts/bench_diagnose_gap.sh: diagnose_gap on an hour of flight (simulated once, cached).
#   5. scripts/bench_diagnose_ulog.sh: diagnose_gap and estimate on an hour of PX4 ULog (simulated once, cached).
#   6. scripts/bench_fleet.sh: fleet on 200 simulated flights (simulated once, cached): flight-hours per core-second.
# QUICK=1 (make bench QUICK=1) tries the pipeline: one round of 10 s per system, 500 messages under callgrind, no
# diagnose_gap, and the document goes to the work directory instead of docs/BENCHMARKS.md.
# Usage, after `make build` and `source .ws/install/setup.sh`: scripts/run_benchmarks.sh [WORK_DIR]
set -euo pipefail
export PATH=/usr/bin:$PATH
repo="$(cd "$(dirname "$0")/.." && pwd)"
# Paths relative to the repository, as the document shows the commands.
cd "$repo"
bin=.ws/build/propulsion_estimator/devel/lib/propulsion_estimator
work="${1:-.ws/bench}"
quick="${QUICK:-0}"
if [ "$quick" = 1 ]; then
  duration_s="${BENCH_DURATION_S:-10}"
  rounds="${BENCH_ROUNDS:-1}"
  callgrind_messages="${BENCH_CALLGRIND_MESSAGES:-500}"
  document="$work/BENCHMARKS.md"
else
  duration_s="${BENCH_DURATION_S:-60}"
  rounds="${BENCH_ROUNDS:-2}"
  callgrind_messages="${BENCH_CALLGRIND_MESSAGES:-2000}"
  document=docs/BENCHMARKS.md
fi
for program in bench_estimator bench_rcout_decode bench_fit bench_simulate bench_probe bench_floor_node estimator_node; do
  if [ ! -x "$bin/$program" ]; then
    echo "run_benchmarks.sh: no $bin/$program (install libbenchmark-dev, then make build)" >&2
    exit 1
  fi
done
mkdir -p "$work"
rm -rf "$work/node"
rm -f "$work"/*.json "$work"/*.txt "$work/commands.tsv"
started=$(date +%s)
# Each section's command, for the document: section<TAB>command.
commands="$work/commands.tsv"
run() {
  local section="$1"
  shift
  printf '%s\t%s\n' "$section" "$*" >>"$commands"
  "$@"
}
date -u +%Y-%m-%dT%H:%M:%SZ >"$work/started_utc.txt"
cut -d' ' -f1-3 /proc/loadavg >"$work/load_start.txt"
# The commit measured (docs/BENCHMARKS.md itself, rewritten at the end, does not count as a change).
{
  git rev-parse --short HEAD 2>/dev/null || printf unknown
  if git status --porcelain -- . ':!docs/BENCHMARKS.md' 2>/dev/null | grep -q .; then printf ' with uncommitted changes'; fi
} | tr -d '\n' >"$work/commit.txt"

for bench in bench_estimator bench_rcout_decode bench_fit bench_simulate; do
  echo "== $bench"
  run "$bench" "$bin/$bench" --benchmark_out="$work/$bench.json" --benchmark_out_format=json
done

run e2e scripts/bench_node.py --bin "$bin" --repo . --work "$work/node" \
  --duration-s "$duration_s" --rounds "$rounds" --e2e-json "$work/e2e.json"
run callgrind scripts/bench_node.py --bin "$bin" --repo . --work "$work/node" \
  --callgrind-messages "$callgrind_messages" --callgrind-json "$work/callgrind.json"

if [ "$quick" != 1 ]; then
  echo "== diagnose_gap on an hour of flight"
  run diagnose_gap scripts/bench_diagnose_gap.sh "${BENCH_GAP_CACHE:-.ws/bench_diagnose_gap}" "$work/diagnose_gap.json"
  echo "== diagnose_gap and estimate on an hour of PX4 ULog"
  run diagnose_ulog scripts/bench_diagnose_ulog.sh "$bin" "${BENCH_ULOG_CACHE:-.ws/bench_diagnose_ulog}" \
    "$work/diagnose_ulog.json"
  echo "== fleet on 200 flights"
  run fleet scripts/bench_fleet.sh "$bin" "${BENCH_FLEET_CACHE:-.ws/bench_fleet}" "$work/fleet.json"
fi

cut -d' ' -f1-3 /proc/loadavg >"$work/load_end.txt"
echo $(($(date +%s) - started)) >"$work/runtime_s.txt"
make_command="make bench"
[ "$quick" = 1 ] && make_command="$make_command QUICK=1"
for setting in BENCH_DURATION_S BENCH_ROUNDS BENCH_CALLGRIND_MESSAGES; do
  [ -n "${!setting:-}" ] && make_command="$make_command $setting=${!setting}"
done
python3 scripts/write_benchmarks.py --results "$work" --template scripts/benchmarks_template.md \
  --arm64 docs/BENCHMARKS.arm64.md --out "$document" --make-command "$make_command"
echo "make bench: $(cat "$work/runtime_s.txt") s; wrote $document"
