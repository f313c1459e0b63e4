#!/usr/bin/env bash
# Set up (packages + build) and run every test with CTest.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
top="$(dirname "$here")"
bash "$here/setup.sh"
cd "${ACTIVETOUCH_BUILD_DIR:-$top/build}"
ctest --output-on-failure -j "$(nproc)" "$@"
