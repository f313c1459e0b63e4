#!/usr/bin/env bash
# Screenshots of every tab after a paper run, as a person sees them: builds, then runs the window
# under Xvfb with --screenshots, which runs the whole paper experiment, a run over seeds 1-10, its
# comparison with paper_kernel.json over the same seeds and the first active trial the two ended
# differently, in both, and saves one PNG per tab, one of the device panels, one of the protocol
# panel and one of the first lost active trial's replay.
# Usage: bash scripts/screenshots.sh [output dir, default results/screenshots]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
top="$(dirname "$here")"
build="${ACTIVETOUCH_BUILD_DIR:-$top/build}"
out="${1:-$top/results/screenshots}"
bash "$here/setup.sh"
mkdir -p "$out"
xvfb-run -a -s "-screen 0 1920x1200x24" "$build/app/activetouch" --screenshots "$out" "$top/experiments/paper.json"
ls "$out"/*.png
