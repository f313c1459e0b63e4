#!/usr/bin/env bash
# Screenshots of the window as a person sees it, on laptop and desktop screens: builds, then for
# each screen size runs the window under Xvfb with --screenshots, which fits the window to the
# screen, runs the whole paper experiment, a run over seeds 1-10, its comparison with
# paper_kernel.json over the same seeds and the first active trial the two ended differently, in
# both, and saves a PNG of the whole screen (the window with its status bar), one per tab, one of
# the device panels, one of the protocol panel and one of the first lost active trial's replay.
# The tour keeps its settings in its own folder: the user's are untouched.
# Usage: bash scripts/screenshots.sh [output dir, default results/screenshots] [WxH ...]
#        (sizes default to 1280x720 1366x768 1920x1080; each gets a folder of its own)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
top="$(dirname "$here")"
build="${ACTIVETOUCH_BUILD_DIR:-$top/build}"
out="${1:-$top/results/screenshots}"
shift || true
sizes=("$@")
[[ ${#sizes[@]} -gt 0 ]] || sizes=(1280x720 1366x768 1920x1080)
bash "$here/setup.sh"
for size in "${sizes[@]}"; do
  mkdir -p "$out/$size"
  xvfb-run -a -s "-screen 0 ${size}x24" \
    "$build/app/activetouch" --screenshots "$out/$size" "$top/experiments/paper.json"
  ls "$out/$size"/*.png
done
