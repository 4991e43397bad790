#!/usr/bin/env python3
"""Closest point, REF vertices -> TEST, end to end: `roving measure` against CloudCompare's C2M.

The question users ask first of a distance tool: how long from the files to the distances, and in
how much memory. Both tools are run as they are used, each in its own process (wall time,
user + system CPU time and peak resident memory from os.wait4), interleaved run by run so that both
see the same machine. `roving measure --semantics closest --samples vertices --hausdorff-bound none`
loads both models, computes REF's vertex normals (for the sign), builds Embree's BVH over TEST and
queries; `CloudCompare -SILENT -O REF -O TEST -c2m_dist` loads both, builds its octree and
computes the signed distance of every REF vertex to TEST (it saves nothing in the timed runs).

Checked before timed: one more run of each writes the per-vertex distances (our --samples-out,
CloudCompare's PLY with its scalar field); |d| must agree on every vertex within CloudCompare's
float rounding (its coordinates and distances are float: 8 ulps of the largest coordinate). Above
PER_VERTEX_LIMIT vertices, the figures over every vertex instead (check_figures).
The signs are not compared: ours is along REF's normal, CloudCompare's along TEST's face.

    python3 bench/cloudcompare_c2m.py --roving build/roving/roving \\
        --pair build/datasets/scaling/ref-n8.ply build/datasets/scaling/test-n8.ply --out results
"""
import argparse
import concurrent.futures
import csv
import multiprocessing
import json
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np


PER_VERTEX_LIMIT = 20_000_000  # vertices; larger pairs are checked by their figures (check_figures)


def run(command, env=None):
    """Runs one process: (wall seconds, CPU seconds, peak RSS in MiB). Raises on failure."""
    start = time.monotonic()
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env)
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.monotonic() - start
    output = process.stdout.read().decode(errors="replace")
    code = os.waitstatus_to_exitcode(status)
    if code != 0:
        raise RuntimeError(f"{' '.join(command)} failed ({code}):\n{output[-2000:]}")
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024, output


def cloudcompare_command(binary, ref, test, save=None):
    command = [binary, "-SILENT", "-AUTO_SAVE", "OFF", "-O", ref, "-O", test, "-c2m_dist"]
    if save:
        command += ["-M_EXPORT_FMT", "PLY", "-PLY_EXPORT_FMT", "BINARY_LE", "-SAVE_MESHES", "FILE", f"{save} {save}.test.ply"]
    return command


def roving_command(binary, ref, test, report, samples_out=None):
    command = [binary, "measure", ref, test, "--semantics", "closest", "--samples", "vertices",
               "--hausdorff-bound", "none", "--quiet", "--json", report]
    if samples_out:
        command += ["--samples-out", samples_out]
    return command


def read_ply_vertex_property(path, name):
    """One float property of a binary little-endian PLY's vertices, with all vertex coordinates."""
    with open(path, "rb") as file:
        data = file.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    count, fields, in_vertex = 0, [], False
    sizes = {"float": "<f4", "double": "<f8", "int": "<i4", "uchar": "u1", "uint": "<u4"}
    for line in header:
        words = line.split()
        if words[:2] == ["element", "vertex"]:
            count, in_vertex = int(words[2]), True
        elif words[:1] == ["element"]:
            in_vertex = False
        elif in_vertex and words[:1] == ["property"]:
            fields.append((words[2], sizes[words[1]]))
    vertices = np.frombuffer(data, dtype=np.dtype(fields), count=count, offset=end)
    xyz = np.stack([vertices["x"], vertices["y"], vertices["z"]], axis=1).astype(np.float64)
    return xyz, vertices[name].astype(np.float64)


def check(roving, cloudcompare, ref, test, env, folder):
    """Both tools' per-vertex |d| on the same pair: vertices compared, largest difference, the
    difference allowed, CloudCompare's version."""
    samples = os.path.join(folder, "samples.csv")
    run(roving_command(roving, ref, test, os.path.join(folder, "check.json"), samples))
    saved = os.path.join(folder, "c2m.ply")
    run(cloudcompare_command(cloudcompare, ref, test, saved), env)
    xyz, theirs = read_ply_vertex_property(saved, "scalar_C2M_signed_distances")
    ours = {}
    with open(samples) as file:
        for row in csv.DictReader(file):
            if row["hit"] == "1":
                ours[int(row["element"])] = abs(float(row["d"]))
    index = np.fromiter(ours.keys(), dtype=np.int64)
    difference = np.abs(np.fromiter(ours.values(), dtype=np.float64) - np.abs(theirs[index]))
    allowed = 8 * np.spacing(np.float32(np.abs(xyz).max()))
    return len(index), float(difference.max()), float(allowed), cloudcompare_version(saved)


def cloudcompare_version(saved):
    """The version CloudCompare's PLY header names: "Created by CloudCompare v2.11.3"."""
    with open(saved, "rb") as file:
        header = file.read(4096).decode(errors="replace")
    return header.split("CloudCompare v", 1)[1].split()[0] if "CloudCompare v" in header else "(version unknown)"


def vertex_count(path):
    with open(path, "rb") as file:
        header = file.read(65536).split(b"end_header", 1)[0].decode(errors="replace")
    return next(int(line.split()[2]) for line in header.splitlines() if line.startswith("element vertex"))


def referenced_vertices(path, count):
    """Which of a binary PLY's `count` vertices its triangles use (a uchar count, then 32-bit indices)."""
    with open(path, "rb") as file:
        head = file.read(65536)
    end = head.index(b"end_header\n") + len(b"end_header\n")
    faces = np.memmap(path, dtype=np.dtype([("n", "u1"), ("v", "<i4", 3)]), mode="r", offset=end + 12 * count)
    used = np.zeros(count, dtype=bool)
    for start in range(0, len(faces), 1 << 24):
        used[faces["v"][start:start + (1 << 24)].ravel()] = True
    return used


def check_figures(roving, cloudcompare, ref, test, env, folder):
    """As check(), where a CSV row per vertex would be too big (15 GB at 5 10^7 vertices): the figures
    over every vertex instead, mean, largest and nearest-rank percentiles of |d|. Were every vertex's
    |d| within e of CloudCompare's, each of these would be too, so a figure further apart than e
    means a vertex is; the converse is not checked."""
    report = os.path.join(folder, "check.json")
    run(roving_command(roving, ref, test, report))
    with open(report) as file:
        ours = json.load(file)["statistics"]
    saved = os.path.join(folder, "c2m.ply")
    run(cloudcompare_command(cloudcompare, ref, test, saved), env)
    xyz, theirs = read_ply_vertex_property(saved, "scalar_C2M_signed_distances")
    theirs = np.abs(theirs[referenced_vertices(ref, len(xyz))])  # our vertex samples skip unreferenced ones
    ranks = {f"p{p}": int(np.ceil(p / 100 * len(theirs))) - 1 for p in (50, 90, 95, 99)}
    ordered = np.partition(theirs, sorted(ranks.values()))
    figures = {"usiad": theirs.mean(), "max_abs": theirs.max(), **{k: ordered[r] for k, r in ranks.items()}}
    difference = max(abs(ours[k] - v) for k, v in figures.items())
    allowed = 8 * np.spacing(np.float32(np.abs(xyz).max()))
    version = cloudcompare_version(saved)
    os.unlink(saved)
    return len(theirs), float(difference), float(allowed), version


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--roving", default="build/roving/roving")
    parser.add_argument("--cloudcompare", default="CloudCompare")
    parser.add_argument("--pair", nargs=2, action="append", metavar=("REF", "TEST"),
                        help="a pair to compare (repeatable; default: the scaling pairs n=8 and n=12)")
    parser.add_argument("--runs", type=int, default=3, help="timed runs of each tool per pair (default 3)")
    parser.add_argument("--out", default="results", help="folder for cloudcompare-c2m.md")
    args = parser.parse_args()
    cloudcompare = shutil.which(args.cloudcompare)
    if not cloudcompare:
        sys.exit(f"cloudcompare_c2m.py: CloudCompare not found as '{args.cloudcompare}' "
                 "(Debian: apt install cloudcompare; or pass --cloudcompare PATH)")
    pairs = args.pair or [[f"build/datasets/scaling/ref-n{n}.ply", f"build/datasets/scaling/test-n{n}.ply"]
                          for n in (8, 12)]
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")  # no display needed
    version = "(version unknown)"
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for ref, test in pairs:
            # The check reads millions of rows: in a process of its own, so that this one stays small
            # (a child's peak RSS counts the parent's memory it was forked from).
            by_figures = vertex_count(ref) > PER_VERTEX_LIMIT
            with concurrent.futures.ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
                compared, largest, allowed, version = pool.submit(
                    check_figures if by_figures else check, args.roving, cloudcompare, ref, test, env, folder).result()
            print(f"{ref}: |d| of {compared} vertices, largest difference {largest:.2e} (allowed {allowed:.2e})",
                  file=sys.stderr)
            if not largest <= allowed:
                sys.exit(f"cloudcompare_c2m.py: the answers differ on {ref} -> {test}: refusing to time them")
            ours, theirs, stages = [], [], []
            report = os.path.join(folder, "timed.json")
            for _ in range(args.runs):
                ours.append(run(roving_command(args.roving, ref, test, report))[:3])
                with open(report) as file:
                    stages.append(json.load(file)["seconds"])
                theirs.append(run(cloudcompare_command(cloudcompare, ref, test), env)[:3])
            rows.append((ref, test, compared, largest, by_figures, ours, theirs, stages))
    write_markdown(args.out, rows, version, args.runs)


def write_markdown(out, rows, version, runs):
    median = lambda values: statistics.median(values)
    lines = [
        "# Closest point end to end: roving against CloudCompare's C2M",
        "",
        "Produced by `bash scripts/cloudcompare-c2m.sh` (`bench/cloudcompare_c2m.py`, needs `apt install cloudcompare`).",
        "REF's vertices to TEST's surface, signed, from the files to the distances: `roving measure --semantics "
        "closest --samples vertices --hausdorff-bound none` (Embree point queries; the vertex normals computed for "
        f"the sign) against `CloudCompare -SILENT -O REF -O TEST -c2m_dist` (CloudCompare {version}, its octree). "
        f"Each its own process, {runs} interleaved runs each, medians; CPU is user + system time, memory the peak "
        "resident set (os.wait4). Checked first: |d| on every vertex the same within CloudCompare's float rounding; "
        f"on pairs of more than {PER_VERTEX_LIMIT:,} vertices (marked *figures*), where a CSV row per vertex would "
        "take 15 GB, the mean, largest and 50th to 99th percentiles of |d| over every vertex instead (each within "
        "the rounding were every vertex). A REF of more than 2^20 faces is streamed (docs/measuring.md's "
        "`--chunk`): its faces read a block at a time for the vertex normals, then its vertices measured a block "
        "at a time; roving does not hold its faces.",
        "",
        f"Machine: {platform.machine()}, {os.cpu_count()} cores, {platform.platform()}.",
        "",
        "| pair | vertices | largest |d| difference | tool | wall s | CPU s | peak MiB | wall ratio | memory ratio |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for ref, test, compared, largest, by_figures, ours, theirs, stages in rows:
        name = f"{os.path.basename(ref)} / {os.path.basename(test)}"
        ow, oc, om = (median([r[i] for r in ours]) for i in range(3))
        tw, tc, tm = (median([r[i] for r in theirs]) for i in range(3))
        lines.append(f"| {name} | {compared:,} | {largest:.1e}{' (figures)' if by_figures else ''} | roving | {ow:.2f} | {oc:.2f} | {om:.0f} | "
                     f"{tw / ow:.2f}x faster | {om / tm:.2f} |")
        lines.append(f"| | | | CloudCompare | {tw:.2f} | {tc:.2f} | {tm:.0f} | 1 | 1 |")
    lines += ["", "Where roving's time goes (medians of the timed runs' `--json` seconds). A streamed REF is read "
              "(its vertices, then its faces once, for the summary and the vertex normals' sums) while TEST loads "
              "and its BVH is built beside it, so those three overlap: other is the wall less the query and the "
              "longer of load REF and load TEST + build, i.e. making the samples, the statistics, process start "
              "and exit:", "",
              "| pair | load REF s | load TEST s | build s | query s | other s | wall s |", "|---|---|---|---|---|---|---|"]
    for ref, test, compared, largest, by_figures, ours, theirs, stages in rows:
        part = {key: median([s[key] for s in stages]) for key in ("load_reference", "load_test", "build", "query")}
        wall = median([r[0] for r in ours])
        other = wall - part["query"] - max(part["load_reference"], part["load_test"] + part["build"])
        lines.append(f"| {os.path.basename(ref)} / {os.path.basename(test)} | {part['load_reference']:.2f} | "
                     f"{part['load_test']:.2f} | {part['build']:.2f} | {part['query']:.2f} | "
                     f"{other:.2f} | {wall:.2f} |")
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "cloudcompare-c2m.md"), "w") as file:
        file.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
