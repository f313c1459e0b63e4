#!/usr/bin/env bash
# Set up (packages + build) and run the main job on the simulated rig: the paper experiment,
# headless, writing results/paper (summary.json, data/, figures/).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
top="$(dirname "$here")"
build="${ACTIVETOUCH_BUILD_DIR:-$top/build}"
bash "$here/setup.sh"
out="${1:-$top/results/paper}"
"$build/app/activetouch-cli" run "$top/experiments/paper.json" --out "$out"
echo "results written to $out (summary.json, data/, figures/)"
