#!/usr/bin/env bash
# The production code's size by layer and its largest files (docs/design.md §1): lines of
# core/, devices/ and app/ (.cpp and .h), app/'s share of them, and every .cpp over 400 lines.
#   bash scripts/code-size.sh
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
lines() { find "$1" \( -name '*.cpp' -o -name '*.h' \) -print0 | xargs -0 cat | wc -l; }
core=$(lines core) devices=$(lines devices) app=$(lines app)
total=$((core + devices + app))
printf 'core %6d\ndevices %3d\napp %7d  (%s %% of %d)\n' "$core" "$devices" "$app" \
  "$(awk -v a="$app" -v t="$total" 'BEGIN { printf "%.1f", 100 * a / t }')" "$total"
echo "largest .cpp files:"
find core devices app -name '*.cpp' -print0 | xargs -0 wc -l | grep -v ' total$' | sort -rn |
  awk '$1 > 400 { printf "  %5d %s\n", $1, $2 }'
