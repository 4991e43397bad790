#!/usr/bin/env bash
# results/examples/report.html and its screenshot report.png (the README shows it): the bunny and
# its 10,459-triangle mesh, both directions, by the cooperative method, as `roving measure --html`
# writes it, photographed by headless Chromium as tests/browser/ drives it. Run by scripts/main.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p results/examples
./build/roving/roving measure build/datasets/bunny.ply build/datasets/bunny-10459.ply --symmetric --method cooperative \
  --html results/examples/report.html --quiet > /dev/null
/usr/bin/python3 - <<'PY'
import sys
sys.path.insert(0, "tests/browser")
import chromium
with chromium.Browser(1400, 860) as browser:
    browser.open("results/examples/report.html")
    if browser.errors:
        sys.exit(f"results/examples/report.html: {browser.errors}")
    open("results/examples/report.png", "wb").write(browser.screenshot())
PY
