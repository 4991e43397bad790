#!/usr/bin/env python3
"""The scaling benchmark: every method on the bunny split into n^2 (69 k to 10 M triangles).

Runs `roving measure REF TEST --json` once per size and method, each in its own process so that
its peak resident memory is its own (os.wait4's ru_maxrss). Writes results/scaling.md (load,
build, query, samples/s, peak RSS and bytes per reference triangle; the fitted growth exponent
of each method's query time) and results/scaling.png. Answers are checked before they are
reported: each method's USiAD against Embree's with the same semantics on the same pair.

    python3 bench/scaling.py --roving build/roving/roving --data build/datasets/scaling --out results
"""
import argparse
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time

SIZES = [1, 2, 4, 8, 12]

# name, arguments, semantics (for the reference it is checked against), tolerance on USiAD
# relative to the reference's (the method's own: float rays 1e-6; GL 1% by the cooperative bound).
METHODS = [
    ("embree first-hit", ["--method", "embree"], "first-hit", None),
    ("embree closest", ["--method", "embree", "--semantics", "closest"], "closest", None),
    ("cgal first-hit", ["--method", "cgal"], "first-hit", 1e-6),
    ("roving", ["--method", "roving"], "first-hit", 2e-3),
    ("cooperative 24x12", ["--method", "cooperative"], "first-hit", 1e-2),
    ("cooperative auto", ["--method", "cooperative", "--views", "auto"], "first-hit", 1e-2),
    ("v2p-aabb", ["--method", "v2p-aabb"], "closest", 1e-6),
    ("v2v-kdtree", ["--method", "v2v-kdtree"], "closest", None),  # vertex distances: not comparable
    ("4 shards of embree first-hit + merge", ["--method", "embree"], "first-hit", 0.0),
    ("4 shards of roving + merge", ["--method", "roving"], "first-hit", 2e-3),
]

# Measured as `measure --shard I/N` processes one after the other, then `roving merge`: its USiAD
# must be Embree's bit for bit (tolerance 0); exact roving's (cut at its 4,096-camera batches) must
# be the one-process roving row's bit for bit (SAME_AS).
SHARDED = {"4 shards of embree first-hit + merge": 4, "4 shards of roving + merge": 4}
SAME_AS = {"4 shards of roving + merge": "roving"}


def run(roving, ref, test, arguments, timeout):
    """One measurement in its own process: (report, peak RSS in bytes, wall seconds)."""
    with tempfile.NamedTemporaryFile(suffix=".json", delete=False) as out:
        report_path = out.name
    # The distance methods alone: under closest semantics `measure` would also certify the Hausdorff
    # distance by default (its own cost, timed in results/README.md), not what this table compares.
    command = [roving, "measure", ref, test, "--json", report_path, "--quiet", "--hausdorff-bound", "none"] + arguments
    start = time.monotonic()
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        _, status, usage = os.wait4(process.pid, 0)
    except KeyboardInterrupt:
        process.kill()
        raise
    wall = time.monotonic() - start
    process.returncode = os.waitstatus_to_exitcode(status)
    stderr = process.stderr.read().decode()
    if process.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed ({process.returncode}): {stderr.strip()}")
    with open(report_path) as file:
        report = json.load(file)
    os.unlink(report_path)
    return report, usage.ru_maxrss * 1024, wall


def run_sharded(roving, ref, test, arguments, shards, timeout):
    """The same measurement as `shards` shard processes in turn and their merge: (the merged report,
    the largest process's peak RSS, the processes' summed wall seconds)."""
    with tempfile.TemporaryDirectory() as folder:
        parts, peak, wall = [], 0, 0.0
        for i in range(shards):
            parts.append(os.path.join(folder, f"{i}.part"))
            _, rss, seconds = run(roving, ref, test, arguments + ["--shard", f"{i}/{shards}", "--shard-out", parts[-1]],
                                  timeout)
            peak, wall = max(peak, rss), wall + seconds
        merged = os.path.join(folder, "merged.json")
        start = time.monotonic()
        process = subprocess.Popen([roving, "merge", *parts, "--json", merged, "--quiet"], stdout=subprocess.DEVNULL,
                                   stderr=subprocess.PIPE)
        _, status, usage = os.wait4(process.pid, 0)
        if os.waitstatus_to_exitcode(status) != 0:
            raise RuntimeError(f"roving merge failed: {process.stderr.read().decode().strip()}")
        with open(merged) as file:
            report = json.load(file)
        return report, max(peak, usage.ru_maxrss * 1024), wall + time.monotonic() - start


def fit_exponent(points):
    """Least-squares slope of log(time) against log(triangles)."""
    points = [(math.log(x), math.log(y)) for x, y in points if x > 0 and y > 0]
    if len(points) < 2:
        return None
    mean_x = sum(x for x, _ in points) / len(points)
    mean_y = sum(y for _, y in points) / len(points)
    spread = sum((x - mean_x) ** 2 for x, _ in points)
    return sum((x - mean_x) * (y - mean_y) for x, y in points) / spread if spread else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--roving", default="build/roving/roving")
    parser.add_argument("--data", default="build/datasets/scaling")
    parser.add_argument("--out", default="results")
    parser.add_argument("--sizes", default=",".join(map(str, SIZES)), help="values of n, comma-separated")
    parser.add_argument("--budget", type=float, default=240,
                        help="seconds a method may take at one size; a size it is predicted to exceed "
                             "(linear growth from the last) is skipped")
    args = parser.parse_args()
    sizes = [int(n) for n in args.sizes.split(",")]

    rows = []  # dicts per (method, size)
    for n in sizes:
        ref, test = (os.path.join(args.data, f"{kind}-n{n}.ply") for kind in ("ref", "test"))
        for name, arguments, semantics, tolerance in METHODS:
            previous = [r for r in rows if r["method"] == name]
            if previous:
                last = previous[-1]
                predicted = last["wall"] * (n * n) / (last["n"] ** 2)
                if predicted > args.budget:
                    print(f"n = {n:2}: {name}: skipped (predicted {predicted:.0f} s > {args.budget:.0f} s)",
                          file=sys.stderr)
                    rows.append({"method": name, "n": n, "skipped": predicted})
                    continue
            if name in SHARDED:
                report, rss, wall = run_sharded(args.roving, ref, test, arguments, SHARDED[name], args.budget)
            else:
                report, rss, wall = run(args.roving, ref, test, arguments, args.budget)
            seconds = report["seconds"]
            row = {
                "method": name, "n": n, "semantics": semantics, "tolerance": tolerance,
                "triangles": report["reference"]["triangles"], "test_triangles": report["test"]["triangles"],
                "samples": report["samples"]["count"], "load": seconds["load_reference"] + seconds["load_test"],
                "build": seconds["build"], "query": seconds["query"], "total": seconds["total"], "wall": wall,
                "rss": rss, "usiad": report["statistics"]["usiad"], "no_hits": report["no_hits"],
                "observations": report.get("gl", {}).get("observations"),
            }
            rows.append(row)
            print(f"n = {n:2}: {name}: query {row['query']:.3f} s, wall {wall:.2f} s, "
                  f"{rss / 2**20:.0f} MiB", file=sys.stderr)

    # Check every answer against Embree's with the same semantics on the same pair.
    failures = []
    for row in rows:
        if "skipped" in row:
            continue
        reference = next(r for r in rows if r["n"] == row["n"] and r.get("semantics") == row["semantics"]
                         and r["method"].startswith("embree"))
        row["error"] = abs(row["usiad"] - reference["usiad"]) / reference["usiad"]
        if row["tolerance"] is not None and row["error"] > row["tolerance"]:
            failures.append(f"{row['method']} at n = {row['n']}: USiAD {row['usiad']:.6g} vs Embree's "
                            f"{reference['usiad']:.6g} ({row['error']:.2e} > {row['tolerance']:.0e})")

    for row in rows:
        if row["method"] in SAME_AS and "skipped" not in row:
            one = next((r for r in rows if r["n"] == row["n"] and r["method"] == SAME_AS[row["method"]]
                        and "skipped" not in r), None)
            if one is None or row["usiad"] != one["usiad"]:
                failures.append(f"{row['method']} at n = {row['n']}: USiAD {row['usiad']!r} is not the one-process "
                                f"{SAME_AS[row['method']]}'s {one and one['usiad']!r}")

    write_markdown(rows, failures, args)
    write_plot(rows, os.path.join(args.out, "scaling.png"))
    if failures:
        print("\n".join(failures), file=sys.stderr)
        return 1
    return 0


def write_markdown(rows, failures, args):
    measured = [r for r in rows if "skipped" not in r]
    lines = [
        "# Scaling: every method from 69 k to 10 M triangles",
        "",
        "Produced by `bash scripts/scaling.sh` (`bench/scaling.py`). REF: the normalised bunny with every triangle",
        "split into n^2; TEST: its 10,459-triangle decimation, perturbed by 0.5% of the diagonal, split alike",
        "(`roving-datasets --scaling`). Face samples of REF (one per triangle), h = 5% of the diagonal. Each run",
        "is its own `roving measure` process: load is both files, build the acceleration structures or",
        "uploads, query the measurement; peak RSS is the process's (`ru_maxrss`). Checked before reported:",
        "USiAD against Embree's with the same semantics (CGAL 1e-6, roving 0.2%, cooperative 1%, v2p 1e-6).",
        "The sharded rows run 4 `roving measure --shard I/4` processes one after the other and then",
        "`roving merge` (docs/batch.md): their times are summed over the shards, their peak RSS is the largest",
        "process's (a shard reads REF as one process does: a block of faces at a time where it has more than 2^20,",
        "and then only as far as its slice); Embree's sharded USiAD must equal Embree's bit for bit,",
        "exact roving's (cut at multiples of its 4,096-camera batches) the one-process roving row's.",
        "Beyond 10 M: results/streaming.md (`bench/streaming.py`) measures REF at 10^8 triangles, streamed a",
        "block of faces at a time, read whole, and in 2 shards + merge, against the same TEST.",
        "",
        f"Machine: {platform.machine()}, {os.cpu_count()} cores, {platform.platform()}.",
        "",
        "| method | n | REF triangles | TEST triangles | load s | build s | query s | samples/s | peak RSS MiB "
        "| bytes / REF triangle | USiAD vs Embree |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for row in rows:
        if "skipped" in row:
            lines.append(f"| {row['method']} | {row['n']} | | | | | skipped: predicted {row['skipped']:.0f} s > "
                         f"{args.budget:.0f} s | | | | |")
            continue
        check = "(reference)" if row["method"].startswith("embree") else (
            f"{row['error']:.1e}" + ("" if row["tolerance"] is None else
                                     (" ok" if row["error"] <= row["tolerance"] else " **FAIL**")))
        lines.append(
            f"| {row['method']} | {row['n']} | {row['triangles']:,} | {row['test_triangles']:,} | {row['load']:.2f} "
            f"| {row['build']:.2f} | {row['query']:.2f} | {row['samples'] / row['query']:.3g} "
            f"| {row['rss'] / 2**20:.0f} | {row['rss'] / row['triangles']:.0f} | {check} |")
    lines += ["", "Growth of the query time with the number of REF triangles (least-squares slope on log-log axes;",
              "1 is linear):", "", "| method | exponent | sizes |", "|---|---|---|"]
    for name, *_ in METHODS:
        points = [(r["triangles"], r["query"]) for r in measured if r["method"] == name]
        exponent = fit_exponent(points)
        lines.append(f"| {name} | {'' if exponent is None else f'{exponent:.2f}'} | {len(points)} |")
    if failures:
        lines += ["", "**Answers that failed their check:**", ""] + [f"- {f}" for f in failures]
    lines += ["", "![query time and memory against size](scaling.png)", ""]
    with open(os.path.join(args.out, "scaling.md"), "w") as file:
        file.write("\n".join(lines))


def write_plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    measured = [r for r in rows if "skipped" not in r]
    figure, (time_axis, memory_axis) = plt.subplots(1, 2, figsize=(12, 4.8), constrained_layout=True)
    for name, *_ in METHODS:
        mine = [r for r in measured if r["method"] == name]
        if not mine:
            continue
        triangles = [r["triangles"] for r in mine]
        time_axis.loglog(triangles, [r["query"] for r in mine], marker="o", label=name)
        memory_axis.semilogx(triangles, [r["rss"] / r["triangles"] for r in mine], marker="o", label=name)
    time_axis.set(xlabel="REF triangles (face samples)", ylabel="query time (s)",
                  title="Query time (log-log)")
    memory_axis.set(xlabel="REF triangles", ylabel="peak RSS / REF triangle (bytes)",
                    title="Peak memory per reference triangle")
    memory_axis.axhline(150, color="grey", linestyle="--", linewidth=1)
    memory_axis.annotate("150 B goal", (measured[0]["triangles"], 150), textcoords="offset points",
                         xytext=(4, 4), color="grey")
    for axis in (time_axis, memory_axis):
        axis.grid(True, which="both", alpha=0.3)
    time_axis.legend(fontsize=8)
    figure.savefig(path, dpi=120)


if __name__ == "__main__":
    sys.exit(main())
