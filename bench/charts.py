#!/usr/bin/env python3
"""Draws roving-bench's charts from the CSVs it writes under RESULTS/charts/, as SVG and PNG.

    python3 bench/charts.py results

Figure 6 is the paper's two histograms (exact roving, cooperative) with Embree's outlined on
each, and a third panel of each method's per-bin difference from Embree, in integer counts.
The H x V study plots error, time and observations against the view settings actually run
(ticks at those settings), one panel against the spacing at 1024 px and one against the
resolution at 24x12. Needs matplotlib; roving-bench itself does not.
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
matplotlib.rcParams["svg.hashsalt"] = "roving"  # the same SVG for the same data, run after run
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter, MaxNLocator  # noqa: E402

EMBREE, ROVING, COOPERATIVE = "#555555", "#d62728", "#1f77b4"
thousands = FuncFormatter(lambda value, _: f"{value:,.0f}")


def read(path):
    with open(path, newline="") as file:
        return list(csv.DictReader(file))


def save(figure, stem):
    for suffix in (".svg", ".png"):
        figure.savefig(stem.with_suffix(suffix), dpi=120, metadata={"Date": None} if suffix == ".svg" else {"Software": None})
    plt.close(figure)


def figure6(rows, stem):
    low = [float(r["bin_low"]) for r in rows]
    width = float(rows[0]["bin_high"]) - low[0]
    counts = {m: [int(r[m]) for r in rows] for m in ("embree", "roving", "cooperative")}
    figure, axes = plt.subplots(1, 3, figsize=(14, 4.2), constrained_layout=True)
    for axis, method, colour, title in (
        (axes[0], "roving", ROVING, "exact roving (GL)"),
        (axes[1], "cooperative", COOPERATIVE, "cooperative 24x12 (GL)"),
    ):
        axis.bar(low, counts[method], width=width, align="edge", color=colour, alpha=0.75, label=title)
        axis.stairs(counts["embree"], low + [low[-1] + width], color=EMBREE, linewidth=1.2,
                    label="Embree (exact reference)")
        axis.set_title(title)
        axis.set_xlabel("signed distance d (paper units; longest side 128)")
        axis.set_ylabel("samples per bin")
        axis.yaxis.set_major_formatter(thousands)
        axis.legend(loc="upper left", frameon=False)
    difference = axes[2]
    centres = [x + width / 2 for x in low]
    for method, colour, label, shift in (
        ("roving", ROVING, "exact roving - Embree", -width / 4),
        ("cooperative", COOPERATIVE, "cooperative - Embree", width / 4),
    ):
        delta = [a - b for a, b in zip(counts[method], counts["embree"])]
        difference.bar([c + shift for c in centres], delta, width=width / 2, color=colour, label=label)
    difference.axhline(0, color=EMBREE, linewidth=0.8)
    difference.yaxis.set_major_locator(MaxNLocator(integer=True))
    difference.yaxis.set_major_formatter(thousands)
    difference.set_title("per-bin difference from Embree")
    difference.set_xlabel("signed distance d (paper units)")
    difference.set_ylabel("samples (method - Embree)")
    difference.legend(loc="upper left", frameon=False)
    figure.suptitle(f"Figure 6: bunny against its 800-triangle mesh, h = 5% of the diagonal "
                    f"(Embree: {sum(counts['embree']):,} hits in [{low[0]:g}, {low[-1] + width:g}])")
    save(figure, stem)


def h_x_v(rows, stem):
    for r in rows:
        r["error"] = abs(float(r["usiad"]) - float(r["embree_usiad"])) / float(r["embree_usiad"]) * 100
    spacing = [r for r in rows if r["resolution"] == "1024"]
    resolution = sorted((r for r in rows if (r["views_h"], r["views_v"]) == ("24", "12")),
                        key=lambda r: int(r["resolution"]))
    figure, axes = plt.subplots(2, 2, figsize=(12, 7.5), constrained_layout=True)
    for column, subset, key, xlabel in (
        (0, spacing, lambda r: int(r["views_h"]) * int(r["views_v"]), "view directions H x V (1024 px views)"),
        (1, resolution, lambda r: int(r["resolution"]), "view resolution, pixels per side (24x12 views)"),
    ):
        x = [key(r) for r in subset]
        labels = [f'{r["views_h"]}x{r["views_v"]}' if column == 0 else r["resolution"] for r in subset]
        top, bottom = axes[0][column], axes[1][column]
        top.plot(x, [r["error"] for r in subset], "o-", color=ROVING, label="|USiAD - USiAD(Embree)|")
        top.axhline(1.0, color=EMBREE, linestyle="--", linewidth=1, label="1% bound")
        top.set_yscale("log")
        top.set_ylabel("USiAD error, % of Embree's")
        top.legend(loc="center right", frameon=False)
        bottom.plot(x, [float(r["query_s"]) for r in subset], "o-", color=COOPERATIVE, label="query seconds")
        bottom.set_ylabel("query seconds", color=COOPERATIVE)
        bottom.set_ylim(bottom=0)
        counts = bottom.twinx()
        counts.plot(x, [int(r["views_rendered"]) for r in subset], "s--", color="#2ca02c", label="views rendered")
        counts.plot(x, [int(r["cameras"]) for r in subset], "^--", color="#9467bd", label="per-sample cameras")
        counts.set_ylabel("observations")
        counts.set_ylim(bottom=0)
        counts.yaxis.set_major_formatter(thousands)
        handles = bottom.get_legend_handles_labels()[0] + counts.get_legend_handles_labels()[0]
        bottom.legend(handles, [h.get_label() for h in handles], loc="center left", framealpha=0.9)
        bottom.set_xlabel(xlabel)
        for axis in (top, bottom):
            axis.set_xscale("log")
            axis.set_xticks(x)
            axis.set_xticklabels(labels)
            axis.minorticks_off()
            axis.grid(True, which="major", alpha=0.3)
    figure.suptitle("H x V study: bunny against its 10,459-triangle mesh, cooperative method (first hit)")
    save(figure, stem)


def main(results):
    charts = Path(results) / "charts"
    figure6(read(charts / "figure6.csv"), charts / "figure6")
    h_x_v(read(charts / "h-x-v.csv"), charts / "h-x-v")
    print(f"charts written to {charts}/ (figure6, h-x-v; .svg and .png)")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results")
