#!/usr/bin/env bash
# Sets up, builds and runs the test suite (CTest + GoogleTest). Real models from ../shared/data
# or $ROVING_DATA.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh browser  # chromium: the web page is tested in a real browser
bash scripts/build.sh
ctest --test-dir build --output-on-failure --timeout 600 -j "$(nproc)"
