#!/usr/bin/env bash
# Set up, build the benchmarks and print each figure beside its budget (docs/benchmarks.md).
# Benchmarks measure; they never fail on time.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
top="$(dirname "$here")"
build="${ACTIVETOUCH_BUILD_DIR:-$top/build}"
bash "$here/setup.sh"
cmake --build "$build" --target benchmarks
export ACTIVETOUCH_RESOURCES="$top/resources"
"$build/tests/bench_classifier"
"$build/tests/bench_simulation"
QT_QPA_PLATFORM="${QT_QPA_PLATFORM:-offscreen}" "$build/tests/bench_paper"
QT_QPA_PLATFORM="${QT_QPA_PLATFORM:-offscreen}" "$build/tests/bench_live"
