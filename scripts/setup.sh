#!/usr/bin/env bash
# Installs the Debian packages listed in scripts/apt-packages.txt that are not yet installed,
# then configures and builds the workbench with Ninja into build/ (or $ACTIVETOUCH_BUILD_DIR).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
top="$(dirname "$here")"
build="${ACTIVETOUCH_BUILD_DIR:-$top/build}"

mapfile -t wanted < <(grep -vE '^\s*(#|$)' "$here/apt-packages.txt" | awk '{print $1}')
missing=()
for p in "${wanted[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "setup: these packages are missing and installing them needs root: ${missing[*]}" >&2
    exit 1
  fi
  echo "setup: installing ${missing[*]}"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

cmake -S "$top" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE="${ACTIVETOUCH_BUILD_TYPE:-Release}" ${ACTIVETOUCH_CMAKE_ARGS:-} >/dev/null
cmake --build "$build" -j "$(nproc)"
