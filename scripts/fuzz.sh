#!/usr/bin/env bash
# Fuzzes every parser of outside data (docs/fuzzing.md): builds the libFuzzer harnesses with
# clang under AddressSanitizer + UndefinedBehaviorSanitizer into build-fuzz/ (or
# $ACTIVETOUCH_FUZZ_BUILD_DIR), then runs each from its checked-in corpus, as many at a time as
# there are cores, for SECONDS (default 60) or until it has run $ACTIVETOUCH_FUZZ_RUNS inputs
# (default 1,000,000), whichever comes first, and prints each harness's executions and findings.
#   bash scripts/fuzz.sh [SECONDS] [HARNESS...]     e.g. bash scripts/fuzz.sh 600
# New inputs the fuzzer finds go to build-fuzz/corpus/<harness>/, never into the repository; a
# finding is written to build-fuzz/findings/<harness>/ and the script exits 1.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
top="$(dirname "$here")"
seconds="${1:-60}"
shift || true
build="${ACTIVETOUCH_FUZZ_BUILD_DIR:-$top/build-fuzz}"
ACTIVETOUCH_BUILD_DIR="$build" ACTIVETOUCH_BUILD_TYPE=RelWithDebInfo \
  ACTIVETOUCH_CMAKE_ARGS="-DACTIVETOUCH_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++" \
  bash "$here/setup.sh"
if [ $# -gt 0 ]; then harnesses=("$@"); else
  mapfile -t harnesses < <(cd "$top/fuzz/corpus" && ls)
fi
export ACTIVETOUCH_RESOURCES="$top/resources"
# The file harnesses write each input to a file: in memory where the machine has /dev/shm.
if [ -z "${TMPDIR:-}" ] && [ -d /dev/shm ] && [ -w /dev/shm ]; then export TMPDIR=/dev/shm; fi
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
run_one() {
  local name="$1" work="$build/corpus/$1" findings="$build/findings/$1"
  mkdir -p "$work" "$findings"
  "$build/fuzz/fuzz_$name" -max_total_time="$seconds" -runs="${ACTIVETOUCH_FUZZ_RUNS:-1000000}" \
    -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$findings/" -print_final_stats=1 "$work" "$top/fuzz/corpus/$name" \
    > "$build/fuzz_$name.log" 2>&1
}
failed=0
pids=()
for name in "${harnesses[@]}"; do
  run_one "$name" &
  pids+=($!)
  if [ ${#pids[@]} -ge "$(nproc)" ]; then wait "${pids[0]}" || true; pids=("${pids[@]:1}"); fi
done
wait || true
printf '%-22s %12s %10s %8s  %s\n' harness executions "per second" seconds findings
for name in "${harnesses[@]}"; do
  log="$build/fuzz_$name.log"
  runs=$(grep -oE 'stat::number_of_executed_units: *[0-9]+' "$log" | grep -oE '[0-9]+$' || echo 0)
  rate=$(grep -oE 'stat::average_exec_per_sec: *[0-9]+' "$log" | grep -oE '[0-9]+$' || echo 0)
  took=$(grep -oE 'Done [0-9]+ runs in [0-9]+ second' "$log" | grep -oE '[0-9]+ second' | grep -oE '[0-9]+' || echo "$seconds")
  found=$(find "$build/findings/$name" -type f | wc -l)
  printf '%-22s %12s %10s %8s  %s\n' "$name" "$runs" "$rate" "${took:-$seconds}" "$found"
  if [ "$found" -gt 0 ] || grep -qE 'ERROR: (AddressSanitizer|libFuzzer)|runtime error:' "$log"; then
    failed=1
    echo "  finding: see $log and $build/findings/$name/" >&2
  fi
done
exit $failed
