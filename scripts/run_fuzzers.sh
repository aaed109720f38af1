#!/bin/bash
# Runs each libFuzzer executable fuzz_<reader> (make fuzz builds them) for a while from a working
# copy of its committed corpus, and prints one line per fuzzer: runs, execs/s, coverage, corpus,
# findings. Findings (crash-*, leak-*, timeout-*, oom-* inputs) and logs go to <work>/findings/
# and <work>/logs/; each run is also appended to <work>/runs.tsv, the record test/fuzz/README.md
# sums. Exits 1 when a fuzzer found something.
#   run_fuzzers.sh --bin DIR --work DIR [--seconds N] [--only a,b] [--merge]
# --merge: afterwards, the inputs of the working corpus that add coverage are merged into
# test/fuzz/corpus/<reader>/ (libFuzzer -merge=1), for the user to review and commit.
set -u
repo="$(cd "$(dirname "$0")/.." && pwd)"
# The fuzzed readers: one corpus folder each, the one list (CMake builds fuzz_<folder> for each).
readers="$(cd "$repo/test/fuzz/corpus" && ls -d -- */ | tr -d / | tr '\n' ' ')"
seconds=60
merge=0
bin=""
work=""
while [ $# -gt 0 ]; do
  case "$1" in
    --bin) bin="$2"; shift 2 ;;
    --work) work="$2"; shift 2 ;;
    --seconds) seconds="$2"; shift 2 ;;
    --only) readers="${2//,/ }"; shift 2 ;;
    --merge) merge=1; shift ;;
    *) echo "run_fuzzers.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
if [ -z "$bin" ] || [ -z "$work" ]; then
  echo "usage: run_fuzzers.sh --bin DIR --work DIR [--seconds N] [--only a,b] [--merge]" >&2
  exit 2
fi

# The longest input worth trying: a little above the largest real file of the kind.
max_len() {
  case "$1" in
    model_yaml|vehicle_urdf|flight_profile) echo 4096 ;;
    bench_csv|tyto_csv) echo 2048 ;;
    flight_manifest) echo 1024 ;;
    rcout|tare_file) echo 256 ;;
    pack_file) echo 1024 ;;
    ulog|dataflash) echo 8192 ;;
    flight_bag) echo 16384 ;;
  esac
}

# Leaks are findings; UBSan's reports are fatal (-fno-sanitize-recover) and print their stack.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:allocator_may_return_null=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
status=0
for reader in $readers; do
  fuzzer="$bin/fuzz_$reader"
  corpus="$work/corpus/$reader"
  findings="$work/findings/$reader"
  log="$work/logs/$reader-$(date -u +%Y%m%dT%H%M%S).log"
  mkdir -p "$corpus" "$findings" "$work/logs"
  cp -n "$repo/test/fuzz/corpus/$reader/"* "$corpus/"
  before=$(find "$findings" -type f | wc -l)
  start=$(date +%s)
  "$fuzzer" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="$(max_len "$reader")" \
    -artifact_prefix="$findings/" -print_final_stats=1 >"$log" 2>&1
  elapsed=$(( $(date +%s) - start ))
  found=$(( $(find "$findings" -type f | wc -l) - before ))
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+' "$log" | tail -1)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$last")
  corp=$(sed -n 's/.* corp: \([0-9]*\).*/\1/p' <<<"$last")
  [ "$found" -gt 0 ] && status=1
  printf '%-16s %5ss  runs %10s  %6s exec/s  cov %5s  corpus %5s  findings %s%s\n' "$reader" "$elapsed" \
    "${runs:-?}" "${rate:-?}" "${cov:-?}" "${corp:-?}" "$found" "$([ "$found" -gt 0 ] && echo "  (see $log)")"
  printf '%s\t%s\t%s\t%s\t%s\n' "$(date -u +%FT%TZ)" "$reader" "$elapsed" "${runs:-?}" "$found" >>"$work/runs.tsv"
  if [ "$merge" = 1 ]; then
    "$fuzzer" -merge=1 -max_len="$(max_len "$reader")" "$repo/test/fuzz/corpus/$reader" "$corpus" >"$log.merge" 2>&1
    echo "  merged: test/fuzz/corpus/$reader has $(find "$repo/test/fuzz/corpus/$reader" -type f | wc -l) files"
  fi
done
exit $status
