#!/usr/bin/env python3
"""Error bars: how the sampled figures move with the sample count, beside their intervals.

For the bunny against its 800- and 10,459-triangle meshes (build/datasets, from roving-datasets):
- USiAD (first hit, Embree) from N = 1e3 ... 1e7 random samples, with its 95% interval;
- the one-sided Hausdorff distance (closest point) sampled from the same N, beside the certified
  interval over the whole surface (--hausdorff-bound 1e-4 of the diagonal);
- what Metro's default sample count (about 10 x the faces of the sampled mesh) and MeshLab's
  Hausdorff filter default (as many samples as the sampled mesh has vertices) amount to;
- coverage: the intervals of 200 seeds at N = 10,000 against USiAD from 1e8 samples (two runs of
  5e7 with their own seeds, averaged: one run of 1e8 would hold about 9 GB of samples).
Every figure comes from `roving measure --json`. Writes results/error-bars.md and, with
matplotlib, results/error-bars.png.

    python3 bench/error_bars.py --roving build/roving/roving --data build/datasets --out results
"""
import argparse
import json
import os
import subprocess
import sys

COUNTS = [1000, 10000, 100000, 1000000, 10000000]
PAIRS = [("bunny-800.ply", "800 triangles"), ("bunny-10459.ply", "10,459 triangles")]
TRUTH_RUNS, TRUTH_SAMPLES = 2, 50000000  # 1e8 samples in all
COVERAGE_SEEDS = 200
COVERAGE_SAMPLES = 10000


def measure(roving, ref, test, *arguments):
    out = subprocess.run([roving, "measure", ref, test, "--json", "-", "--quiet", *arguments],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--roving", default="build/roving/roving")
    parser.add_argument("--data", default="build/datasets")
    parser.add_argument("--out", default="results")
    args = parser.parse_args()
    ref = os.path.join(args.data, "bunny.ply")
    lines = ["# Error bars: sampled figures against their intervals", "",
             "Written by `bench/error_bars.py` (run by `scripts/main.sh`) from `roving measure --json`; do not edit by "
             "hand. REF is the bunny (normalised, longest side 128, 69,451 triangles, 35,947 vertices), TEST its "
             "quadric decimations. USiAD: first hit, Embree, h = 5% of the diagonal, `--samples area:N` (seed 12345), "
             "with the 95% interval of the surface mean (normal approximation). Hausdorff: REF -> TEST, closest point, "
             "the largest distance over the same N samples, beside the certified interval over every point of REF "
             "(`--hausdorff-bound` 1e-4 of the diagonal).", ""]
    chart = {}
    for test_name, label in PAIRS:
        test = os.path.join(args.data, test_name)
        faces = measure(args.roving, ref, test, "--samples", "faces")
        lines += [f"## The bunny against its {label}", "",
                  "| N samples | USiAD | 95% interval | half-width / USiAD | sampled Hausdorff | certified Hausdorff | "
                  "sampled / certified lower |", "|---|---|---|---|---|---|---|"]
        rows = []
        for n in COUNTS:
            print(f"error bars: {label}, N = {n}", file=sys.stderr, flush=True)
            first = measure(args.roving, ref, test, "--samples", f"area:{n}")
            closest = measure(args.roving, ref, test, "--samples", f"area:{n}", "--semantics", "closest",
                              "--hausdorff-bound", "0.01%")
            u = first["sampling_error"]["usiad"]
            h = closest["hausdorff_certified"]
            sampled = closest["statistics"]["max_abs"]
            # Checked before reported: the interval is as narrow as asked and above every sampled distance.
            assert h["upper"] - h["lower"] <= h["bound"] * (1 + 1e-9) and sampled <= h["upper"] * (1 + 1e-9), (n, h)
            rows.append((n, u, sampled, h))
            lines.append(f"| {n:,} | {u['estimate']:.5f} | [{u['lower']:.5f}, {u['upper']:.5f}] | "
                         f"{(u['upper'] - u['lower']) / 2 / u['estimate']:.2%} | {sampled:.4f} | "
                         f"[{h['lower']:.4f}, {h['upper']:.4f}] | {sampled / h['lower']:.3f} |")
        lines += ["", f"Face samples (69,451 centroids), the exact eq. 2 mean over them: USiAD "
                  f"{faces['statistics']['usiad']:.5f}. Metro's default sample count is about 10 x the faces of the "
                  f"sampled mesh (694,510 here), MeshLab's Hausdorff filter's the sampled mesh's vertex count "
                  f"(35,947): between the 1e5 and 1e6 rows, and the 1e4 and 1e5 rows.", ""]
        chart[label] = rows

    # Coverage: how often the 95% interval from 10,000 samples holds the 1e8-sample value.
    test = os.path.join(args.data, "bunny-10459.ply")
    runs = []
    for run in range(TRUTH_RUNS):
        print(f"error bars: coverage, the truth: run {run + 1} of {TRUTH_RUNS}, {TRUTH_SAMPLES:,} samples", file=sys.stderr,
              flush=True)
        runs.append(measure(args.roving, ref, test, "--samples", f"area:{TRUTH_SAMPLES}", "--seed",
                            str(999999 + run))["sampling_error"]["usiad"])
    # Equal-size independent runs: the mean of their means, its standard error sqrt(sum se^2) / runs.
    estimate = sum(r["estimate"] for r in runs) / TRUTH_RUNS
    half_width = 1.959963984540054 * sum(r["standard_error"] ** 2 for r in runs) ** 0.5 / TRUTH_RUNS
    t = {"estimate": estimate, "lower": estimate - half_width, "upper": estimate + half_width}
    covered = 0
    for seed in range(1, COVERAGE_SEEDS + 1):
        if seed % 50 == 0:
            print(f"error bars: coverage, seed {seed} of {COVERAGE_SEEDS}", file=sys.stderr, flush=True)
        u = measure(args.roving, ref, test, "--samples", f"area:{COVERAGE_SAMPLES}", "--seed", str(seed))
        u = u["sampling_error"]["usiad"]
        covered += u["lower"] <= t["estimate"] <= u["upper"]
    lines += ["## Coverage", "",
              f"USiAD of the bunny against its 10,459-triangle mesh from {TRUTH_RUNS * TRUTH_SAMPLES:,} samples "
              f"({TRUTH_RUNS} runs of {TRUTH_SAMPLES:,}, seeds 999999 on): "
              f"{t['estimate']:.6f} (its own interval [{t['lower']:.6f}, {t['upper']:.6f}]). The 95% intervals from "
              f"{COVERAGE_SAMPLES:,} samples with seeds 1 to {COVERAGE_SEEDS} hold it in **{covered} of "
              f"{COVERAGE_SEEDS}** runs ({covered / COVERAGE_SEEDS:.1%}; 95% expected, a binomial standard deviation of "
              f"{(COVERAGE_SEEDS * 0.95 * 0.05) ** 0.5:.1f} runs).", ""]
    with open(os.path.join(args.out, "error-bars.md"), "w") as f:
        f.write("\n".join(lines))

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: results/error-bars.png not drawn", file=sys.stderr)
        return
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for (label, rows), colour in zip(chart.items(), ["tab:blue", "tab:orange"]):
        n = [r[0] for r in rows]
        final = rows[-1][1]["estimate"]  # the largest N's estimate: the pairs' USiAD differ tenfold
        estimate = [100 * (r[1]["estimate"] / final - 1) for r in rows]
        below = [100 * (r[1]["estimate"] - r[1]["lower"]) / final for r in rows]
        above = [100 * (r[1]["upper"] - r[1]["estimate"]) / final for r in rows]
        axes[0].errorbar(n, estimate, yerr=[below, above], marker="o", capsize=4, color=colour,
                         label=f"{label} (USiAD {final:.4f} at N = {n[-1]:.0e})")
        axes[1].plot(n, [r[2] for r in rows], marker="o", color=colour, label=f"{label}: sampled maximum")
        h = rows[-1][3]
        axes[1].axhspan(h["lower"], h["upper"], color=colour, alpha=0.35)
        axes[1].axhline(h["upper"], color=colour, linestyle="--", label=f"{label}: certified [{h['lower']:.3f}, {h['upper']:.3f}]")
    axes[0].set(xscale="log", xlabel="random samples N", ylabel="USiAD against its value at the largest N (%)",
                title="USiAD with its 95% interval")
    axes[1].set(xscale="log", xlabel="random samples N", ylabel="Hausdorff REF -> TEST (paper units)",
                title="sampled Hausdorff against the certified interval")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "error-bars.png"), dpi=110)


if __name__ == "__main__":
    main()
