#!/usr/bin/env python3
"""One pair of any size on one machine: `roving measure` with REF read a block of faces at a time.

Measures the bunny split to 10^7 and 10^8 triangles (REF) against the 1.5 M-triangle TEST, first-hit,
closest (the distances alone: --hausdorff-bound none) and closest with its default certified Hausdorff
interval, and closest by CGAL's AABB tree, each in its own process so that its peak resident memory is
its own (os.wait4's ru_maxrss): streamed (the default, `--chunk` 2^20 faces a block) and read whole
(`--chunk 0`); REF as binary PLY, and first-hit also as binary STL and as OBJ. Checked before
reported: the streamed report's figures equal the whole one's, every field but the times and how it
ran; the certified intervals, bounded a block at a time, meet the whole run's and are as narrow as
asked. Writes results/streaming.md with wall time, peak RSS, bytes per REF triangle and samples/s, and
the two goals: peak RSS <= 2.5 GB at 10^8, and the 10^8 wall within 1.15x of the 10^7 wall scaled by
the triangles (linear).

The pairs come from roving-datasets (made here when missing):
    python3 bench/streaming.py --roving build/roving/roving --datasets build/datasets_gen/roving-datasets \\
        --data build/datasets-streaming --out results
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time

GOAL_RSS = 2.5e9  # bytes, at 10^8 triangles
GOAL_LINEAR = 1.15  # the 10^8 wall over the 10^7 wall times the triangles' ratio
SHARDS = 2
SHARDED = f"{SHARDS} shards + merge"  # one process after another, as a Slurm array's tasks would be

# (name, REF file, semantics, arguments, modes)
RUNS = [
    ("10^7", "scaling/ref-n12.ply", "first-hit", [], ["streamed", "whole", SHARDED]),
    ("10^7", "scaling/ref-n12.ply", "closest", ["--semantics", "closest"], ["streamed", "whole"]),
    ("10^8", "scaling-large/ref-n38.ply", "first-hit", [], ["streamed", "whole", SHARDED]),
    ("10^8", "scaling-large/ref-n38.ply", "closest", ["--semantics", "closest"], ["streamed"]),
    ("10^7", "scaling/ref-n12.ply", "closest, certified", ["--semantics", "closest", "--hausdorff-bound", "0.01%"],
     ["streamed", "whole"]),
    ("10^8", "scaling-large/ref-n38.ply", "closest, certified",
     ["--semantics", "closest", "--hausdorff-bound", "0.01%"], ["streamed"]),
    # CGAL's AABB tree over TEST in place of Embree's BVH.
    ("10^7", "scaling/ref-n12.ply", "closest, CGAL", ["--semantics", "closest", "--method", "cgal"],
     ["streamed", "whole"]),
    ("10^8", "scaling-large/ref-n38.ply", "closest, CGAL", ["--semantics", "closest", "--method", "cgal"], ["streamed"]),
    # Exact surface roving, its one-pixel cameras drawn by GL (llvmpipe here), 4,096 to a batch.
    ("10^7", "scaling/ref-n12.ply", "first-hit, GL roving", ["--method", "roving"], ["streamed", "whole"]),
    ("10^8", "scaling-large/ref-n38.ply", "first-hit, GL roving", ["--method", "roving"], ["streamed"]),
    # The same REF as binary STL and as OBJ, the other formats a REF streams from.
    ("10^7", "scaling-large/ref-n12.stl", "first-hit", [], ["streamed", "whole"]),
    ("10^8", "scaling-large/ref-n38.stl", "first-hit", [], ["streamed"]),
    ("10^7", "scaling-large/ref-n12.obj", "first-hit", [], ["streamed", "whole"]),
    ("10^8", "scaling-large/ref-n38.obj", "first-hit", [], ["streamed"]),
]
SCALING_LARGE = "scaling-large/ref-n38.obj"  # the last file roving-datasets --scaling-large writes
TEST = "scaling/test-n12.ply"
FORMATS = {".ply": "binary PLY", ".stl": "binary STL", ".obj": "OBJ"}
INCIDENTAL = {"seconds", "command_line", "provenance", "streamed", "tool", "merged_from"}


def measure(roving, ref, test, arguments):
    """One `roving measure` process: (report, peak RSS bytes, wall seconds)."""
    with tempfile.NamedTemporaryFile(suffix=".json", delete=False) as out:
        report_path = out.name
    bound = [] if "--hausdorff-bound" in arguments else ["--hausdorff-bound", "none"]
    rss, wall = run([roving, "measure", ref, test, "--json", report_path, "--quiet"] + bound + arguments)
    with open(report_path) as file:
        report = json.load(file)
    os.unlink(report_path)
    return report, rss, wall


def run(command):
    """One process: (peak RSS bytes, wall seconds). Raises on failure."""
    start = time.monotonic()
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.monotonic() - start
    if os.waitstatus_to_exitcode(status) != 0:
        raise RuntimeError(f"{' '.join(command)} failed: {process.stderr.read().decode().strip()}")
    return usage.ru_maxrss * 1024, wall


def measure_sharded(roving, ref, test, arguments):
    """SHARDS `roving measure --shard i/N` processes and `roving merge`: (merged report, the largest
    peak RSS, the walls summed). Each shard streams REF as far as its slice (docs/batch.md)."""
    with tempfile.TemporaryDirectory() as folder:
        parts = [os.path.join(folder, f"{i}.part") for i in range(SHARDS)]
        report_path = os.path.join(folder, "merged.json")
        bound = [] if "--hausdorff-bound" in arguments else ["--hausdorff-bound", "none"]
        runs = [run([roving, "measure", ref, test, "--shard", f"{i}/{SHARDS}", "--shard-out", parts[i], "--quiet"]
                    + bound + arguments) for i in range(SHARDS)]
        runs.append(run([roving, "merge", *parts, "--json", report_path, "--quiet"]))
        with open(report_path) as file:
            report = json.load(file)
    return report, max(rss for rss, _ in runs), sum(wall for _, wall in runs)


def figures(report):
    """The report without the fields that say how long or how it ran."""
    if isinstance(report, dict):
        return {k: figures(v) for k, v in report.items() if k not in INCIDENTAL and not k.endswith("_seconds")}
    if isinstance(report, list):
        return [figures(v) for v in report]
    return report


def check_interval(what, report):
    """The certified interval as narrow as asked and above every sample's distance."""
    h = report["hausdorff_certified"]
    failures = []
    if h["upper"] - h["lower"] > h["bound"]:
        failures.append(f"{what}: the certified interval is wider than asked")
    if h["upper"] < report["statistics"]["max_abs"]:
        failures.append(f"{what}: a sample lies farther than the certified upper end")
    return failures


def compare(what, streamed, whole):
    """Failures where the streamed report's figures differ from the whole one's. A certified interval
    bounded a block at a time may differ from the whole run's within its width: both must hold the
    truth, so they must meet."""
    failures = []
    if "hausdorff_certified" in whole:
        failures += check_interval(what, streamed)
        a, b = streamed["hausdorff_certified"], whole["hausdorff_certified"]
        if a["lower"] > b["upper"] or b["lower"] > a["upper"]:
            failures.append(f"{what}: the streamed and whole certified intervals do not meet")
        streamed, whole = dict(streamed), dict(whole)
        del streamed["hausdorff_certified"], whole["hausdorff_certified"]
    if figures(streamed) != figures(whole):
        failures.append(f"{what}: the streamed report's figures differ from the whole one's")
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--roving", default="build/roving/roving")
    parser.add_argument("--datasets", default="build/datasets_gen/roving-datasets", help="roving-datasets, to make the pairs")
    parser.add_argument("--data", default="build/datasets-streaming", help="folder of the pairs (made when missing)")
    parser.add_argument("--out", default="results")
    args = parser.parse_args()
    for flag, path in (("--scaling", TEST), ("--scaling-large", SCALING_LARGE)):
        if not os.path.exists(os.path.join(args.data, path)):
            print(f"making the pairs: roving-datasets {flag}", file=sys.stderr)
            subprocess.run([args.datasets, flag, "--out", args.data], check=True, stdout=subprocess.DEVNULL)

    rows, failures = [], []
    for size, ref, semantics, arguments, modes in RUNS:
        form = FORMATS[os.path.splitext(ref)[1]]
        what = f"{size} {form} {semantics}"
        reports = {}
        for mode in modes:
            paths = os.path.join(args.data, ref), os.path.join(args.data, TEST)
            if mode == SHARDED:
                report, rss, wall = measure_sharded(args.roving, *paths, arguments)
            else:
                report, rss, wall = measure(args.roving, *paths, arguments + (["--chunk", "0"] if mode == "whole" else []))
            if (mode == "streamed") != ("streamed" in report["samples"]):
                failures.append(f"{what} {mode}: the report says the reference was "
                                f"{'read whole' if mode == 'streamed' else 'streamed'}")
            reports[mode] = report
            rows.append({"size": size, "format": form, "semantics": semantics, "mode": mode, "wall": wall, "rss": rss,
                         "triangles": report["reference"]["triangles"], "samples": report["samples"]["count"],
                         "load": report["seconds"]["load_reference"], "query": report["seconds"]["query"],
                         "usiad": report["statistics"]["usiad"],
                         "certified": report.get("hausdorff_certified", {}).get("seconds")})
            print(f"{what} {mode}: {wall:.1f} s, {rss / 2**20:.0f} MiB", file=sys.stderr)
        if "whole" in reports:
            failures += compare(what, reports["streamed"], reports["whole"])
        if SHARDED in reports:
            failures += compare(f"{what} {SHARDED}", reports[SHARDED], reports["streamed"])
        elif "hausdorff_certified" in reports["streamed"]:
            failures += check_interval(what, reports["streamed"])
    write_markdown(rows, failures, args)
    if failures:
        print("\n".join(failures), file=sys.stderr)
        return 1
    return 0


def write_markdown(rows, failures, args):
    def row_of(size, form, semantics, mode):
        return next((r for r in rows if (r["size"], r["format"], r["semantics"], r["mode"]) ==
                     (size, form, semantics, mode)), None)

    lines = [
        "# One pair of any size: REF streamed a block of faces at a time",
        "",
        "Produced by `python3 bench/streaming.py` (pairs from `roving-datasets --scaling` and `--scaling-large`).",
        "REF: the normalised bunny with every triangle split into 12^2 (10^7 triangles) and 38^2 (10^8), as",
        "binary PLY, and as binary STL and OBJ (its float coordinates in the fewest digits that read back); TEST:",
        "its 10,459-triangle decimation, perturbed by 0.5% of the diagonal, split into 12^2 (1.5 M triangles).",
        "Face samples (one per REF triangle), h = 5% of the diagonal, Embree (*CGAL*: CGAL's AABB tree; *GL roving*: exact",
        "surface roving's one-pixel cameras, `--method roving`, drawn by Mesa's llvmpipe); *closest* is the distances alone",
        "(`--hausdorff-bound none`), *closest, certified* adds the certified Hausdorff interval at its default",
        "width (0.01% of the diagonal), bounded a block at a time when streamed. Each run",
        "is its own `roving measure` process; peak RSS is its `ru_maxrss`. *streamed*: the default, REF read,",
        "sampled and measured 2^20 faces at a time (`--chunk`, docs/measuring.md); *whole*: `--chunk 0`, REF",
        "loaded and sampled at once; *2 shards + merge*: `--shard 0/2` and `1/2` (each streams REF up to its slice's end) and",
        "`roving merge`, one after another as a Slurm array's tasks would run (wall: the three summed; peak RSS:",
        "the largest). Checked before reported: each streamed report's figures equal the whole one's and the",
        "merged one's (every JSON field but the times).",
        "",
        f"Machine: {platform.machine()}, {os.cpu_count()} cores, {platform.platform()}.",
        "",
        "| REF | REF file | semantics | REF read | wall s | load REF s | query s | certified bound s "
        "| samples/s (wall) | peak RSS MiB | bytes / REF triangle |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(f"| {r['size']} ({r['triangles']:,}) | {r['format']} | {r['semantics']} | {r['mode']} | {r['wall']:.1f} "
                     f"| {r['load']:.1f} | {r['query']:.1f} "
                     f"| {'-' if r['certified'] is None else format(r['certified'], '.1f')} "
                     f"| {r['samples'] / r['wall']:.3g} | {r['rss'] / 2**20:,.0f} "
                     f"| {r['rss'] / r['triangles']:.1f} |")
    lines += ["", "Goals at 10^8 (streamed):", ""]
    for form, semantics in [(f, s) for f in FORMATS.values() for s in ("first-hit", "closest", "closest, certified", "closest, CGAL", "first-hit, GL roving")]:
        small, large = row_of("10^7", form, semantics, "streamed"), row_of("10^8", form, semantics, "streamed")
        if not (small and large):
            continue
        linear = large["wall"] / (small["wall"] * large["triangles"] / small["triangles"])
        lines.append(f"- {form}, {semantics}: peak RSS {large['rss'] / 1e9:.2f} GB (goal <= {GOAL_RSS / 1e9:.1f}: "
                     f"{'met' if large['rss'] <= GOAL_RSS else '**missed**'}); wall {large['wall']:.1f} s against "
                     f"{small['wall']:.1f} s x {large['triangles'] / small['triangles']:.2f} = {linear:.2f}x linear "
                     f"(goal <= {GOAL_LINEAR}: {'met' if linear <= GOAL_LINEAR else '**missed**'}).")
    whole, streamed = row_of("10^8", "binary PLY", "first-hit", "whole"), row_of("10^8", "binary PLY", "first-hit", "streamed")
    if whole and streamed:
        lines.append(f"- Against reading the PLY REF whole at 10^8 (first-hit): {whole['wall'] / streamed['wall']:.2f}x the "
                     f"speed in {whole['rss'] / streamed['rss']:.1f}x less memory.")
    lines += [
        "",
        "What a streamed run holds: TEST's search structure, REF's vertices (a PLY's as the file stores them,",
        "12 bytes each in float; an OBJ's as parsed, 24 bytes in double; an STL's none: it stores each facet's",
        "corners, and its first pass counts the distinct corners in a set freed before the measurement), one",
        "block of faces with its samples and distances (about 100 MB at 2^20 faces), and per sample 8 bytes:",
        "|d| in double, from which the exact percentiles and the heat-map range the JSON reports are read.",
        "Exact roving (*GL roving*) draws its one-pixel cameras 4,096 tiles to a batch, and a streamed REF hands",
        "it whole batches (the rest carried into the next block), so each camera is drawn at the tile a whole",
        "run gives it and the figures are the same. Viewpoint sampling and cooperative read REF whole: each",
        "view is drawn for every sample at once (docs/measuring.md says which options need REF whole).",
        "",
        "The certified interval of a streamed REF is bounded in a pass of its own over the same blocks, each",
        "a small mesh of its faces (4 bytes more per REF vertex for their numbering) against TEST's closest-",
        "point structure, pruning with the best lower bound so far: it holds the true value within the width",
        "asked, as the whole run's does, and its ends may differ from the whole run's within that width.",
        "",
        "Checks: " + ("every streamed report equals the whole one's figures and the merged shards'; the certified intervals meet "
                      "the whole run's and are as narrow as asked." if not failures else
                      "**FAILED**: " + "; ".join(failures)),
        "",
    ]
    with open(os.path.join(args.out, "streaming.md"), "w") as file:
        file.write("\n".join(lines))


if __name__ == "__main__":
    sys.exit(main())
