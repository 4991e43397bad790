#!/usr/bin/env python3
"""MPEG's point-cloud figures, end to end: `roving measure --pcc` against MPEG's own pc_error.

Both are run as codec evaluations run them, each in its own process from the files to the figures
(wall time, CPU time and peak resident memory from os.wait4), interleaved run by run so that both
see the same machine: pc_error on its default one thread and with --nbThreads=2, roving on both
cores. Checked before timed: every geometry and colour PSNR must agree within 1e-6 dB.

The pair is made here (or given with --pair): N points voxelised on a torus at 11 bits with unit
normals and colours (A), and A requantised to a step of 2 and jittered by one voxel, with noisy
colours and no normals (B) - a geometry codec's output, duplicates and ties included. pc_error is
not part of roving: build it from https://github.com/MPEGGroup/mpeg-pcc-dmetric (release-v0.14.2)
with its optimisation flags (`cmake -S source -B build -DCMAKE_BUILD_TYPE=Release`); its own build.sh
and a plain `cmake -S source -B build` give no build type, so no -O flag at all, and a pc_error about
1.6x slower: give that one too with --pc-error-unoptimised to time it beside.

    python3 bench/pc_error_speed.py --roving build/roving/roving --pc-error /path/to/Release/pc_error \\
        --pc-error-unoptimised /path/to/build.sh/pc_error --points 1000000 10000000 --runs 3 --out results
"""
import argparse
import json
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time


def run(command):
    """One process: (wall s, CPU s, peak RSS MiB, output). Raises on failure."""
    start = time.monotonic()
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.monotonic() - start
    output = process.stdout.read().decode(errors="replace")
    if os.waitstatus_to_exitcode(status) != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{output[-2000:]}")
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024, output


def write_ply(path, points, normals, colours):
    import numpy as np

    fields = [("x", "<f4"), ("y", "<f4"), ("z", "<f4")]
    header = ["property float x", "property float y", "property float z"]
    if normals is not None:
        fields += [("nx", "<f4"), ("ny", "<f4"), ("nz", "<f4")]
        header += ["property float nx", "property float ny", "property float nz"]
    fields += [("red", "u1"), ("green", "u1"), ("blue", "u1")]
    header += ["property uchar red", "property uchar green", "property uchar blue"]
    rows = np.zeros(len(points), dtype=fields)
    rows["x"], rows["y"], rows["z"] = points.T
    if normals is not None:
        rows["nx"], rows["ny"], rows["nz"] = normals.T
    rows["red"], rows["green"], rows["blue"] = colours.T
    with open(path, "wb") as f:
        f.write(f"ply\nformat binary_little_endian 1.0\nelement vertex {len(points)}\n".encode())
        f.write(("\n".join(header) + "\nend_header\n").encode())
        f.write(rows.tobytes())


def make_pair(n, folder):
    import numpy as np
    rng = np.random.Generator(np.random.PCG64(1))
    side = 2 ** 11
    u, v = rng.uniform(0, 2 * np.pi, size=(2, n))
    big, small = 0.3 * side, 0.12 * side
    surface = np.stack([(big + small * np.cos(v)) * np.cos(u), (big + small * np.cos(v)) * np.sin(u),
                        small * np.sin(v)], axis=1)
    ring = np.stack([big * np.cos(u), big * np.sin(u), np.zeros_like(u)], axis=1)
    normals = (surface - ring) / small
    a = np.round(side / 2 + surface)
    colours = np.clip(np.round(127.5 + 127.5 * np.sin(a / 40 + np.array([0, 2, 4]))), 0, 255).astype(np.uint8)
    b = np.round(a / 2) * 2 + rng.integers(-1, 2, size=a.shape)
    noisy = np.clip(colours.astype(int) + rng.integers(-10, 11, size=colours.shape), 0, 255).astype(np.uint8)
    paths = os.path.join(folder, f"torus-{n}-a.ply"), os.path.join(folder, f"torus-{n}-b.ply")
    write_ply(paths[0], a, normals, colours)
    write_ply(paths[1], b, None, noisy)
    return paths


def pc_error_figures(output):
    """The symmetric PSNRs pc_error prints."""
    found = {}
    for key, pattern in {"d1_psnr": r"mseF,PSNR \(p2point\): (\S+)", "d2_psnr": r"mseF,PSNR \(p2plane\): (\S+)",
                         "y_psnr": r"c\[0\],PSNRF\s*: (\S+)", "cb_psnr": r"c\[1\],PSNRF\s*: (\S+)",
                         "cr_psnr": r"c\[2\],PSNRF\s*: (\S+)"}.items():
        match = re.search(pattern, output)
        if match:
            found[key] = float(match.group(1))
    return found


def timed_section(args, count, folder):
    """The answers checked, then the interleaved timings of one pair: a Markdown section."""
    if not args.pair:
        subprocess.run([sys.executable, __file__, "--make-pair", folder, "--points", str(count),
                        "--roving", args.roving, "--pc-error", args.pc_error], check=True)
    a, b = args.pair or (os.path.join(folder, f"torus-{count}-{x}.ply") for x in "ab")
    report = os.path.join(folder, "report.json")
    tools = {
        "pc_error, 1 thread (its default)": [args.pc_error, f"--fileA={a}", f"--fileB={b}", "--color=1",
                                             "--hausdorff=1", f"--resolution={args.resolution}"],
        "pc_error --nbThreads=2": [args.pc_error, f"--fileA={a}", f"--fileB={b}", "--color=1", "--hausdorff=1",
                                   f"--resolution={args.resolution}", "--nbThreads=2"],
        "roving measure --pcc": [args.roving, "measure", a, b, "--pcc", "--pcc-resolution", args.resolution,
                                 "--quiet", "--json", report],
    }
    if args.pc_error_unoptimised:
        tools["pc_error as its build.sh builds it (no -O), 1 thread"] = [
            args.pc_error_unoptimised, f"--fileA={a}", f"--fileB={b}", "--color=1", "--hausdorff=1",
            f"--resolution={args.resolution}"]
    # The answers first.
    theirs = pc_error_figures(run(tools["pc_error, 1 thread (its default)"])[3])
    run(tools["roving measure --pcc"])
    ours = json.load(open(report))["mpeg_pcc"]
    for key, value in theirs.items():
        if abs(ours["symmetric"][key] - value) > 1e-6:
            sys.exit(f"{key}: roving {ours['symmetric'][key]}, pc_error {value}")
    times = {name: [] for name in tools}
    for _ in range(args.runs):
        for name, command in tools.items():
            times[name].append(run(command)[:3])
    points = ours["points_read"]
    base = statistics.median(t[0] for t in times["pc_error, 1 thread (its default)"])
    lines = [
        f"## A {points[0]:,} points, B {points[1]:,}\n",
        f"Every figure agreed within 1e-6 dB before timing (D1 {theirs.get('d1_psnr')}, D2 "
        f"{theirs.get('d2_psnr')}, Y {theirs.get('y_psnr')} dB). Median of {args.runs} interleaved runs, from the "
        "files to the figures.\n",
        "| tool | wall, s | CPU, s | peak RSS, MiB | speed-up on pc_error's default |",
        "|---|---|---|---|---|"]
    for name, rows in times.items():
        wall = statistics.median(r[0] for r in rows)
        lines.append(f"| {name} | {wall:.2f} | {statistics.median(r[1] for r in rows):.2f} | "
                     f"{statistics.median(r[2] for r in rows):.0f} | {base / wall:.2f}x |")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--roving", required=True, help="the roving executable")
    parser.add_argument("--pc-error", required=True,
                        help="MPEG's pc_error executable (mpeg-pcc-dmetric), built with CMAKE_BUILD_TYPE=Release")
    parser.add_argument("--pc-error-unoptimised", help="pc_error as its build.sh builds it (no build type), to time beside")
    parser.add_argument("--points", type=int, nargs="+", default=[1000000],
                        help="points of each generated pair (one table per size)")
    parser.add_argument("--pair", nargs=2, help="A.ply B.ply instead of the generated pair")
    parser.add_argument("--resolution", default="2047", help="the PSNR peak given to both")
    parser.add_argument("--runs", type=int, default=3, help="timed runs of each (the median is reported)")
    parser.add_argument("--out", help="folder to write pc-error-speed.md to")
    parser.add_argument("--make-pair", help=argparse.SUPPRESS)  # FOLDER: make the pair there (a child process)
    args = parser.parse_args()
    if args.make_pair:
        make_pair(args.points[0], args.make_pair)
        return
    sections = []
    for count in ([None] if args.pair else args.points):
        # Made in a child process: a child forked from a process holding the arrays would count
        # them in its peak RSS.
        with tempfile.TemporaryDirectory() as folder:
            sections.append(timed_section(args, count, folder))
    pair = ("the given pair" if args.pair else
            "a torus voxelised at 11 bits and its requantised copy; normals on A, colour on both")
    text = "\n".join([
        "# MPEG's point-cloud figures: roving against pc_error\n",
        f"Written by `bench/pc_error_speed.py` on {platform.node()} ({os.cpu_count()} cores), "
        f"{time.strftime('%Y-%m-%d')}: {pair}; peak {args.resolution}. pc_error (mpeg-pcc-dmetric "
        "release-v0.14.2) built with `-DCMAKE_BUILD_TYPE=Release` (its -O3 flags); its own build.sh gives no build "
        "type, and so no optimisation, which the last row times where given.\n"] + sections)
    print(text)
    if args.out:
        with open(os.path.join(args.out, "pc-error-speed.md"), "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
