#!/usr/bin/env bash
# Set up (packages + build) and run the workbench on the simulated rig. With a display it opens
# the window on the paper experiment; without one it reproduces the whole paper headless into
# results/paper (summary.json, data/, figures/).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
top="$(dirname "$here")"
build="${ACTIVETOUCH_BUILD_DIR:-$top/build}"
bash "$here/setup.sh"
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ] && [ -z "${ACTIVETOUCH_HEADLESS:-}" ]; then
  exec "$build/app/activetouch" "$top/experiments/paper.json"
fi
out="${1:-$top/results/paper}"
"$build/app/activetouch-cli" run "$top/experiments/paper.json" --out "$out"
echo "results written to $out (summary.json, data/, figures/)"
