#!/usr/bin/env bash
# The install as a user gets it: cmake --install into a fresh prefix, then, with the source tree's
# experiments, resources and docs out of reach (an empty tmpfs over each, in a mount namespace of
# its own), the installed activetouch-cli runs the installed paper.json and writes its figures;
# the desktop entry passes desktop-file-validate; both binaries say their version.
# Usage: check-install.sh <build dir> <source dir> <version>
set -euo pipefail
build="$1"
source="$2"
version="$3"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
prefix="$work/prefix"

cmake --install "$build" --prefix "$prefix" > "$work/install.log"
for f in bin/activetouch bin/activetouch-cli share/activetouch/experiments/paper.json \
         share/activetouch/resources/fingertip/icub_fingertip_2010.json \
         share/applications/activetouch.desktop share/icons/hicolor/scalable/apps/activetouch.svg \
         share/icons/hicolor/48x48/apps/activetouch.png share/icons/hicolor/256x256/apps/activetouch.png \
         share/doc/activetouch/window.md; do
  [[ -e "$prefix/$f" ]] || { echo "not installed: $f"; exit 1; }
done

desktop-file-validate "$prefix/share/applications/activetouch.desktop"
echo "desktop-file-validate: passed"

[[ "$("$prefix/bin/activetouch" --version)" == "activetouch $version" ]] || { echo "activetouch --version"; exit 1; }
[[ "$("$prefix/bin/activetouch-cli" --version)" == "activetouch-cli $version" ]] || { echo "activetouch-cli --version"; exit 1; }
echo "versions: $("$prefix/bin/activetouch" --version), $("$prefix/bin/activetouch-cli" --version)"

run="$prefix/bin/activetouch-cli run $prefix/share/activetouch/experiments/paper.json --out $work/run"
hide="mount -t tmpfs none '$source/experiments' && mount -t tmpfs none '$source/resources' && mount -t tmpfs none '$source/docs'"
if unshare --mount true 2> /dev/null; then
  unshare --mount sh -c "$hide && [ -z \"\$(ls -A '$source/resources')\" ] && env -u ACTIVETOUCH_RESOURCES $run" > "$work/run.log"
  echo "ran with the source tree's experiments, resources and docs hidden"
else
  echo "this machine cannot make a mount namespace (unshare): the source tree stays in reach"
  env -u ACTIVETOUCH_RESOURCES $run > "$work/run.log"
fi
tail -n 2 "$work/run.log"
for f in summary.json figures/figure6_errors.pdf figures/figure6_errors.png figures/figure8_active_paths.svg; do
  [[ -s "$work/run/$f" ]] || { echo "the installed run did not write $f"; exit 1; }
done
# The figures are journal-sized: a double-column page, fonts embedded.
pdfinfo "$work/run/figures/figure6_errors.pdf" | grep -q "Page size: *505 x" || { pdfinfo "$work/run/figures/figure6_errors.pdf"; exit 1; }
if pdffonts "$work/run/figures/figure6_errors.pdf" | tail -n +3 | awk '{ if ($(NF-4) != "yes") bad = 1 } END { exit bad }'; then
  echo "figures: written, fonts embedded"
else
  pdffonts "$work/run/figures/figure6_errors.pdf"; exit 1
fi
echo "install: passed"
