#!/usr/bin/python3
"""`roving measure --html` and `roving batch --html` in a real browser: Debian's headless Chromium
(software WebGL) loads each page from disk; the test fails on any console error or exception, and
checks from screenshots that the canvas shows the surface in the report's colours, that the colour
bar's labels are the report's range, that picking and the direction toggle work, and that the batch
index sorts and links. Run by CTest: html_page_test.py ROVING WORKDIR. Exit 77 (skipped) without
chromium.

The pair is made so that every colour's share is known: REF is the square [-1, 1]^2 at z = 0 in
40 x 40 cells (face samples, all of equal area); TEST is the half x < 0 at z = -0.02 (d = -0.02,
blue), the quarter 0 < x < 0.5 at z = +0.02 (d = +0.02, red), and nothing over x > 0.5 (no hit,
grey). Seen head-on, each colour's share of the surface's pixels is its share of the samples."""
import io
import json
import os
import pathlib
import re
import subprocess
import sys

import numpy as np
from matplotlib import image

sys.path.insert(0, str(pathlib.Path(__file__).parent))
import chromium  # noqa: E402

roving, work = sys.argv[1], pathlib.Path(sys.argv[2])
if not chromium.find():
    print("skipped: chromium is not installed (apt install chromium; scripts/setup.sh browser does)")
    sys.exit(77)
work.mkdir(parents=True, exist_ok=True)
failures = []


def check(condition, what):
    print(("ok    " if condition else "FAIL  ") + what)
    if not condition:
        failures.append(what)


def grid(path, x0, x1, z, cells_x, cells_y=40, colour=None):
    """A rectangle [x0, x1] x [-1, 1] at height z, facing +z, as an OBJ of cells_x x cells_y quads,
    its vertices coloured `colour` (fractions of 1, MeshLab's `v x y z r g b`) where given."""
    lines = []
    rgb = "" if colour is None else " " + " ".join(f"{c:g}" for c in colour)
    for j in range(cells_y + 1):
        for i in range(cells_x + 1):
            lines.append(f"v {x0 + (x1 - x0) * i / cells_x:.9g} {-1 + 2 * j / cells_y:.9g} {z}{rgb}")
    at = lambda i, j: j * (cells_x + 1) + i + 1  # noqa: E731
    for j in range(cells_y):
        for i in range(cells_x):
            lines.append(f"f {at(i, j)} {at(i + 1, j)} {at(i + 1, j + 1)}")
            lines.append(f"f {at(i, j)} {at(i + 1, j + 1)} {at(i, j + 1)}")
    path.write_text("\n".join(lines) + "\n")


grid(work / "ref.obj", -1, 1, 0, 40)
grid(work / "low.obj", -1, 0, -0.02, 20)
grid(work / "high.obj", 0, 0.5, 0.02, 10)
# TEST: both pieces in one OBJ (the second's indices shifted past the first's vertices).
first = (work / "low.obj").read_text().splitlines()
second = (work / "high.obj").read_text().splitlines()
shift = sum(1 for l in first if l.startswith("v "))
second = [l if not l.startswith("f ") else "f " + " ".join(str(int(i) + shift) for i in l.split()[1:]) for l in second]
(work / "test.obj").write_text("\n".join(first + second) + "\n")

RED, BLUE, GREY = (103, 0, 31), (5, 48, 97), (128, 128, 128)  # the map's ends and the no-hit grey


def colour_shares(png):
    pixels = np.round(image.imread(io.BytesIO(png))[:, :, :3] * 255).astype(int)
    near = lambda c: np.all(np.abs(pixels - np.array(c)) <= 4, axis=2)  # noqa: E731
    counts = {name: int(near(c).sum()) for name, c in (("red", RED), ("blue", BLUE), ("grey", GREY))}
    return counts, pixels.shape[0] * pixels.shape[1]


def check_view(browser, view, report_direction, expected, what):
    """The canvas in the report's colours and shares; the colour bar's labels its range."""
    rect = browser.evaluate("(() => { const r = document.getElementById('view').getBoundingClientRect();"
                            " return {x: r.x, y: r.y, width: r.width, height: r.height}; })()")
    counts, total = colour_shares(browser.screenshot(rect))
    surface = sum(counts.values())
    check(surface > 0.1 * total, f"{what}: the surface covers {surface} of {total} canvas pixels (> 10%)")
    signs = report_direction["signs"]
    samples = report_direction["samples"]["count"]
    shares = {"red": signs["positive"] / samples, "blue": signs["negative"] / samples,
              "grey": report_direction["no_hits"] / samples}
    for name, share in shares.items():
        check(abs(share - expected[name]) < 1e-9, f"{what}: the report's {name} share {share:.4f} is the pair's {expected[name]}")
        seen = counts[name] / max(surface, 1)
        # Pixels on the boundaries between colours are blended by antialiasing: a few per cent.
        check(abs(seen - share) < 0.02, f"{what}: {name} pixels {seen:.4f} of the surface's, samples {share:.4f}")
    range_ = report_direction["heatmap_range"]
    labels = browser.evaluate("[document.getElementById('bar-low').textContent, document.getElementById('bar-high').textContent]")
    low, high = (float(l.replace("\u2212", "-")) for l in labels)
    check(abs(low + range_) <= 5e-4 * range_ and abs(high - range_) <= 5e-4 * range_,
          f"{what}: colour bar labels {labels} are -+ the report's heatmap_range {range_:.6g} (4 digits)")
    check(view["range"] == range_, f"{what}: the page's range {view['range']} is the report's")


def pick(browser, rect, colour):
    """Clicks a pixel of the given colour; returns what the page says about it."""
    pixels = np.round(image.imread(io.BytesIO(browser.screenshot(rect)))[:, :, :3] * 255).astype(int)
    ys, xs = np.nonzero(np.all(np.abs(pixels - np.array(colour)) <= 4, axis=2))
    middle = len(xs) // 2
    browser.click(rect["x"] + xs[middle] + 0.5, rect["y"] + ys[middle] + 0.5)
    return browser.evaluate("document.getElementById('pick').textContent")


def run(*args):
    done = subprocess.run([roving, *map(str, args)], capture_output=True, text=True)
    check(done.returncode == 0, f"roving {' '.join(map(str, args))}: exit {done.returncode} {done.stderr.strip()[-300:]}")


page = work / "pair.html"
run("measure", work / "ref.obj", work / "test.obj", "--symmetric", "--semantics", "first-hit", "--threshold", "1%",
    "--html", page, "--json", work / "pair.json", "--quiet")
report = json.loads((work / "pair.json").read_text())
embedded = re.search(r'<script id="roving-report" type="application/json">(.*?)</script>', page.read_text(), re.S)
check(embedded and json.loads(embedded.group(1))["directions"][0]["statistics"] == report["directions"][0]["statistics"],
      "the page embeds the JSON report")
data = json.loads(re.search(r'<script id="roving-data" type="application/json">(.*?)</script>', page.read_text(), re.S).group(1))

with chromium.Browser() as browser:
    browser.open(page)
    rect = browser.evaluate("(() => { const r = document.getElementById('view').getBoundingClientRect();"
                            " return {x: r.x, y: r.y, width: r.width, height: r.height}; })()")
    check_view(browser, data["views"][0], report["directions"][0], {"red": 0.25, "blue": 0.5, "grey": 0.25}, "A -> B")
    text = pick(browser, rect, BLUE)
    check(re.search(r"sample \d+, d = -0\.02 ", text) is not None, f"clicking blue shows d = -0.02: '{text}'")
    text = pick(browser, rect, GREY)
    check("no hit" in text, f"clicking grey shows a no-hit: '{text}'")
    browser.evaluate("document.querySelectorAll('#directions button')[1].click()")
    # B -> A: the pieces against the square: the low piece (2/3 of B's area) sees it above (red).
    check_view(browser, data["views"][1], report["directions"][1], {"red": 2 / 3, "blue": 1 / 3, "grey": 0}, "B -> A")
    check(browser.evaluate("document.querySelectorAll('section.direction')[1].hidden") is False,
          "the toggle shows B -> A's figures")
    # The provenance as rendered once opened: the tool, the command line and each input's sha256.
    shown = browser.evaluate("(() => { const d = [...document.querySelectorAll('details')].find("
                             "e => e.querySelector('summary').textContent === 'Provenance');"
                             " if (!d) return ''; d.querySelector('summary').click();"
                             " return d.querySelector('table').innerText; })()")
    check(report["command_line"] in shown and all(i["sha256"] in shown for i in report["inputs"])
          and report["tool"]["version"] in shown, f"the Provenance section shows the report's: '{shown[:300]}'")
    # The pair's figures by family, as rendered: both directions' mean |d|, and the reconstruction
    # figures' F-score at the threshold.
    tables = browser.evaluate("[...document.querySelectorAll('section.pair')].map(s => s.innerText)")
    both = next((t for t in tables if t.startswith("Both directions")), "")
    check(f"{report['two_sided']['mean_both']:.6g} (" in both, f"the pair's section shows mean |d| of both: '{both}'")
    f_score = report["reconstruction"]["thresholds"][0]["f_score"]
    reconstruction = next((t for t in tables if t.startswith("Reconstruction figures")), "")
    check(f"{100 * f_score:.4g}%" in reconstruction and "F-score at tau" in reconstruction,
          f"the reconstruction section shows F at tau ({100 * f_score:.4g}%): '{reconstruction}'")
    check(not browser.errors, f"no console error or exception: {browser.errors}")
    outside = [u for u in browser.requests if not u.startswith(("file://", "data:", "about:"))]
    check(browser.requests and not outside, f"the page loads nothing but itself ({len(browser.requests)} requests): {outside}")
    (work / "screenshot.png").write_bytes(browser.screenshot())

# Colour: REF grey (102, 102, 102); TEST's low half the same (delta E 0), its quarter above reddened
# to (204, 102, 102), the rest no hit. The page shows d, delta E, REF's or TEST's colour; each
# layer's colours cover the canvas in the shares of the elements that carry them.
grid(work / "ref-coloured.obj", -1, 1, 0, 40, colour=(0.4, 0.4, 0.4))
grid(work / "low-coloured.obj", -1, 0, -0.02, 20, colour=(0.4, 0.4, 0.4))
grid(work / "high-coloured.obj", 0, 0.5, 0.02, 10, colour=(0.8, 0.4, 0.4))
first = (work / "low-coloured.obj").read_text().splitlines()
second = (work / "high-coloured.obj").read_text().splitlines()
second = [l if not l.startswith("f ") else "f " + " ".join(str(int(i) + shift) for i in l.split()[1:]) for l in second]
(work / "test-coloured.obj").write_text("\n".join(first + second) + "\n")
page = work / "coloured.html"
run("measure", work / "ref-coloured.obj", work / "test-coloured.obj", "--html", page, "--json", work / "coloured.json",
    "--quiet")
report = json.loads((work / "coloured.json").read_text())
view = json.loads(re.search(r'<script id="roving-data" type="application/json">(.*?)</script>', page.read_text(),
                            re.S).group(1))["views"][0]


def layer_shares(encoded):
    """Each colour of a layer (three bytes per face) and the share of the faces it colours."""
    import base64
    colours = np.frombuffer(base64.b64decode(encoded), np.uint8).reshape(-1, 3)
    found, counts = np.unique(colours, axis=0, return_counts=True)
    return {tuple(int(x) for x in c): n / len(colours) for c, n in zip(found, counts)}


with chromium.Browser() as browser:
    browser.open(page)
    rect = browser.evaluate("(() => { const r = document.getElementById('view').getBoundingClientRect();"
                            " return {x: r.x, y: r.y, width: r.width, height: r.height}; })()")
    check(browser.evaluate("document.getElementById('shown').hidden") is False, "colour: the page offers what to show")
    expected = {"delta_e": {"zero": 0.5, "top": 0.25, "grey": 0.25},
                "test": {(102, 102, 102): 0.5, (204, 102, 102): 0.25, GREY: 0.25},
                "reference": {(102, 102, 102): 1.0}}
    for layer in ("delta_e", "test", "reference"):
        browser.evaluate(f"document.querySelector('#shown button[data-show={layer}]').click()")
        shares = layer_shares(view["colours_of"]["delta_e_colours" if layer == "delta_e" else layer])
        want = sorted(expected[layer].values())
        check(sorted(round(v, 9) for v in shares.values()) == want,
              f"colour, {layer}: the layer's colours cover {sorted(shares.values())} of the faces, the pair's {want}")
        pixels = np.round(image.imread(io.BytesIO(browser.screenshot(rect)))[:, :, :3] * 255).astype(int)
        near = {c: int(np.all(np.abs(pixels - np.array(c)) <= 4, axis=2).sum()) for c in shares}
        surface = sum(near.values())
        for colour, share in shares.items():
            seen = near[colour] / max(surface, 1)
            check(abs(seen - share) < 0.02, f"colour, {layer}: {colour} pixels {seen:.4f} of the surface's, faces {share:.4f}")
    browser.evaluate("document.querySelector('#shown button[data-show=delta_e]').click()")
    labels = browser.evaluate("[document.getElementById('bar-low').textContent, document.getElementById('bar-high').textContent,"
                              " document.getElementById('bar-units').textContent]")
    top = view["colours_of"]["delta_e_range"]
    check(labels[0] == "0" and abs(float(labels[1]) - top) <= 5e-4 * top and "CIEDE2000" in labels[2],
          f"colour: delta E's bar runs from 0 to its 99th percentile {top:.4g}: {labels}")
    check(abs(top - report["colour"]["delta_e_max"]) <= 1e-6 * top,
          f"colour: with two delta E values, the top is the report's largest ({report['colour']['delta_e_max']:.6g})")
    browser.evaluate("document.querySelector('#shown button[data-show=test]').click()")
    text = pick(browser, rect, (204, 102, 102))
    check(re.search(r"delta E = [0-9.]+, REF’s colour \(102, 102, 102\), TEST’s \(204, 102, 102\)", text)
          is not None, f"colour: clicking the reddened quarter shows its delta E and both colours: '{text}'")
    browser.evaluate("document.querySelector('#shown button[data-show=d]').click()")
    labels = browser.evaluate("[document.getElementById('bar-low').textContent, document.getElementById('bar-units').textContent]")
    check(labels[0].startswith("\u2212") and labels[1].startswith("d in model units"), f"colour: back to d, its legend: {labels}")
    check(not browser.errors, f"colour: no console error or exception: {browser.errors}")

# --heatmap-of delta-e: the page opens on delta E, the layer asked for, with its legend.
run("measure", work / "ref-coloured.obj", work / "test-coloured.obj", "--heatmap-of", "delta-e", "--html",
    work / "delta-e.html", "--quiet")
with chromium.Browser() as browser:
    browser.open(work / "delta-e.html")
    on = browser.evaluate("[...document.querySelectorAll('#shown button.on')].map(b => b.dataset.show)")
    units = browser.evaluate("document.getElementById('bar-units').textContent")
    check(on == ["delta_e"] and "CIEDE2000" in units, f"--heatmap-of delta-e opens on delta E: {on}, '{units}'")
    check(not browser.errors, f"delta E first: no console error or exception: {browser.errors}")

# A batch of two pairs, one of which fails: the index lists both, sorts, and links to the page.
manifest = work / "pairs.csv"
manifest.write_text("reference,test\nref.obj,test.obj\nref.obj,missing.obj\n")
done = subprocess.run([roving, "batch", manifest, "--out", work / "batch", "--html", "--quiet"], capture_output=True, text=True)
check(done.returncode == 4, f"roving batch --html with a failing pair: exit 4, found {done.returncode}")
with chromium.Browser() as browser:
    browser.open(work / "batch" / "index.html")
    rows = browser.evaluate("Array.from(document.querySelectorAll('tbody tr')).map(r => [r.cells[0].textContent, r.className, r.querySelector('a') ? r.querySelector('a').getAttribute('href') : ''])")
    check([r[0] for r in rows] == ["0", "1"] and rows[1][1] == "failed", f"the index lists both pairs, the failed one marked: {rows}")
    check(rows[0][2].endswith(".html") and (work / "batch" / rows[0][2]).exists(), f"the measured pair links to its page: {rows[0][2]}")
    browser.evaluate("document.querySelector('thead th').click(); document.querySelector('thead th').click()")
    order = browser.evaluate("Array.from(document.querySelectorAll('tbody tr')).map(r => r.cells[0].textContent)")
    check(order == ["1", "0"], f"clicking the index column twice sorts it descending: {order}")
    browser.open(work / "batch" / rows[0][2])
    check(not browser.errors, f"no console error or exception on the index and the pair page: {browser.errors}")

print(f"{len(failures)} failures")
sys.exit(1 if failures else 0)
