#!/usr/bin/env python3
"""The DTU protocol, end to end: `roving measure --protocol dtu` against DTUeval-python's own eval.py.

Each runs in its own process from the files to the figures (wall time, CPU time and peak resident
memory from os.wait4), on the same machine, one after the other: eval.py with its multiprocessing
pool and scikit-learn on every core, roving on every core. Checked before timed: the three figures
must agree to 1e-9 relative. For that both visit the points in their own order: eval.py's one line
of randomness (its unseeded shuffle) is removed in a copy, as tests/data/dtu/record_dtu.sh does;
a shuffle costs either side the same few seconds.

The scene is made here, DTU-sized (millimetres): the ground truth, M points on a sphere; the
reconstruction, a rippled sphere meshed so that eval.py's sampling makes about N points (mesh
mode) or N points on it (--mode pcd); the mask (observed where x < 0.65 R) and the ground plane,
as .mat files. --order says how the files hold their points: `file` (a spiral, as made), `scan`
(scan lines: rows of the x-y plane one after the other, as a scanner writes them) or `random` (a
fixed shuffle, as many reconstruction pipelines write them; a mesh's vertices so, and its faces
shuffled or by their first vertex); both tools read the same files. eval.py is not part of roving:
https://github.com/jzhangbs/DTUeval-python (Debian's python3-open3d, -sklearn, -scipy, -tqdm).

    /usr/bin/python3 bench/dtu_speed.py --roving build/roving/roving --dtueval /path/to/DTUeval-python \\
        --points 1000000 10000000 30000000 [--mode pcd] [--order random] --out results
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy.io


def run(command):
    """One process: (wall s, CPU s, peak RSS MiB, output). Raises on failure."""
    start = time.monotonic()
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    output = b""
    while chunk := process.stdout.read(65536):
        output += chunk
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.monotonic() - start
    text = output.decode(errors="replace")
    if os.waitstatus_to_exitcode(status) != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{text[-2000:]}")
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024, text


def add_rows(lines, rows, points, truth, number):
    """One table row per tool: (name, wall, CPU, RSS, figures), each figure formatted by `number`."""
    for name, wall, cpu, rss, figures in rows:
        lines.append(f"| {points:,} | {truth:,} | {name} | {wall:.1f} | {cpu:.1f} | {rss:,.0f} | "
                     + " | ".join(number.format(v) for v in figures) + " |")
        print(lines[-1], flush=True)


def write_report(lines, ratios, out, name):
    """The ratios under the table; the page to out/name (else stdout only)."""
    if ratios:
        lines.append("")
        for points, speed, memory in ratios:
            lines.append(f"- {points:,} points: roving {speed:.1f}x faster, in {memory:.1f}x less memory.")
    text = "\n".join(lines) + "\n"
    if out:
        os.makedirs(out, exist_ok=True)
        open(os.path.join(out, name), "w").write(text)
    print(text)


def write_ply(path, vertices, faces=None):
    with open(path, "wb") as f:
        header = f"ply\nformat binary_little_endian 1.0\nelement vertex {len(vertices)}\n"
        header += "property float x\nproperty float y\nproperty float z\n"
        if faces is not None:
            header += f"element face {len(faces)}\nproperty list uchar int vertex_indices\n"
        f.write((header + "end_header\n").encode())
        f.write(np.ascontiguousarray(vertices, dtype="<f4").tobytes())
        if faces is not None:
            rows = np.zeros(len(faces), dtype=[("n", "u1"), ("i", "<i4", 3)])
            rows["n"], rows["i"] = 3, faces
            f.write(rows.tobytes())


def order_of(points, order, density):
    """The places of the points as a file in `order` holds them (see the module's text)."""
    if order == "random":
        return np.random.default_rng(1).permutation(len(points))
    if order == "scan":  # rows 2 density apart along y, each along x; rows of z slices
        cells = np.floor(points / (2 * density)).astype(np.int64)
        return np.lexsort((points[:, 0], cells[:, 1], cells[:, 2]))
    return np.arange(len(points))


def ordered(points, order, density):
    """The points as a file in `order` holds them."""
    return points if order == "file" else points[order_of(points, order, density)]


def ordered_mesh(vertices, faces, order, density):
    """A mesh as a file in `order` holds it: its vertices in that order, the faces' corners
    renumbered, and the faces shuffled (random) or by their first vertex in the new order (scan)."""
    if order == "file":
        return vertices, faces
    by = order_of(vertices, order, density)
    place = np.empty(len(by), dtype=np.int64)
    place[by] = np.arange(len(by))
    faces = place[faces]
    faces = faces[np.random.default_rng(2).permutation(len(faces)) if order == "random"
                  else np.argsort(faces.min(1), kind="stable")]
    return vertices[by], faces


def rippled(t, p, radius):
    rr = radius + 0.5 * np.sin(7 * t) * np.sin(5 * p)
    return np.stack([rr * np.sin(t) * np.cos(p), rr * np.sin(t) * np.sin(p), rr * np.cos(t)], -1)


def make_scene(folder, points, truth, density, triangles=0, mode="mesh", order="file"):
    """Files laid out as DTU's data set (scan 1), and the reconstruction (about `triangles` faces
    where given, or `points` points in pcd mode)."""
    # eval.py makes about one point per density^2 of area: a sphere of that area.
    radius = float(np.sqrt(points * density * density / (4 * np.pi)))
    i = np.arange(truth) + 0.5
    z = 1 - 2 * i / truth
    phi = np.pi * (3 - np.sqrt(5)) * i
    r = np.sqrt(1 - z * z)
    os.makedirs(f"{folder}/Points/stl", exist_ok=True)
    os.makedirs(f"{folder}/ObsMask", exist_ok=True)
    write_ply(f"{folder}/Points/stl/stl001_total.ply",
              ordered(radius * np.stack([r * np.cos(phi), r * np.sin(phi), z], 1), order, density))
    if mode == "pcd":  # N points spread evenly over the rippled sphere
        j = np.arange(points) + 0.5
        write_ply(f"{folder}/recon_points.ply",
                  ordered(rippled(np.arccos(1 - 2 * j / points), np.pi * (3 - np.sqrt(5)) * j, radius), order, density))
    # Faces about 10 density steps across (50 samples each), or as many as asked: 4 rings^2.
    rings = max(8, int(np.sqrt(triangles / 4)) if triangles else int(np.pi * radius / (10 * density)))
    segments = 2 * rings
    t, p = np.meshgrid(np.linspace(0, np.pi, rings + 1)[1:-1], np.linspace(0, 2 * np.pi, segments, endpoint=False),
                       indexing="ij")
    vertices = rippled(t, p, radius).reshape(-1, 3)
    a = (np.arange(rings - 2)[:, None] * segments + np.arange(segments)[None, :]).ravel()
    b = (np.arange(rings - 2)[:, None] * segments + (np.arange(segments)[None, :] + 1) % segments).ravel()
    faces = np.concatenate([np.stack([a, a + segments, b], 1), np.stack([b, a + segments, b + segments], 1)])
    write_ply(f"{folder}/recon_mesh.ply", *ordered_mesh(vertices, faces, order, density))
    side = 1.1 * radius
    res = side / 64
    n = int(np.ceil(2 * side / res)) + 1
    x = np.arange(n) * res - side
    observed = np.broadcast_to((x < 0.65 * radius)[:, None, None], (n, n, n)).copy()
    scipy.io.savemat(f"{folder}/ObsMask/ObsMask1_10.mat",
                     {"ObsMask": observed, "BB": np.array([[-side] * 3, [side] * 3]), "Res": res}, do_compression=True)
    scipy.io.savemat(f"{folder}/ObsMask/Plane1.mat", {"P": np.array([[0.0], [0], [1], [0.9 * radius]])})


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--roving", required=True)
    parser.add_argument("--dtueval", help="a DTUeval-python checkout; without it roving alone is timed")
    parser.add_argument("--points", type=int, nargs="+", default=[3000000],
                        help="the reconstruction's points before thinning, one scene per number")
    parser.add_argument("--truth-ratio", type=float, default=10, help="reconstruction points per ground-truth point")
    parser.add_argument("--triangles", type=int, default=0,
                        help="the reconstruction mesh's triangles (else faces 10 sampling steps across); "
                             "writes dtu-speed-dense-mesh.md")
    parser.add_argument("--mode", choices=["mesh", "pcd"], default="mesh",
                        help="the reconstruction a mesh eval.py samples, or N points (eval.py's --mode)")
    parser.add_argument("--order", choices=["file", "scan", "random"], default="file",
                        help="how the files hold their points (the module's text)")
    parser.add_argument("--out", help="a folder for dtu-speed.md; else stdout")
    args = parser.parse_args()
    density = 0.2
    mesh = f"a reconstruction mesh of about {args.triangles:,} triangles" if args.triangles else "a reconstruction mesh"
    if args.mode == "pcd":
        mesh = "a reconstruction of N points"
    order = {"file": "in the points' own order (a spiral)", "scan": "the files in scan order (rows along x)",
             "random": "the files in random order (a fixed shuffle)"}[args.order]
    lines = [
        "# The DTU protocol: roving against DTUeval-python",
        "",
        f"Written by `bench/dtu_speed.py --points {' '.join(map(str, args.points))}"
        + (f" --triangles {args.triangles} --truth-ratio {args.truth_ratio:g}" if args.triangles else "")
        + (f" --mode {args.mode}" if args.mode != "mesh" else "") + (f" --order {args.order}" if args.order != "file" else "")
        + f"` on {platform.node()} ({os.cpu_count()} cores), {time.strftime('%Y-%m-%d')}. Each scene: {mesh} that eval.py samples "
        f"into about N points, against a ground truth of N / {args.truth_ratio:g} points. One run each, {order}, "
        "eval.py's shuffle left out so that both visit them so; the figures agree to 1e-9 relative before anything "
        "is timed.",
        "",
        "| points sampled | ground truth | tool | wall s | CPU s | peak RSS MiB | accuracy | completeness | overall |",
        "| ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    ratios = []
    for points in args.points:
        truth = int(points / args.truth_ratio)
        with tempfile.TemporaryDirectory() as folder:
            # In a process of its own: a child's peak RSS counts its parent's at the fork (Linux copies
            # the high-water mark), so this process stays small while the scene's arrays are made.
            run([sys.executable, __file__, "--make-scene", folder, str(points), str(truth), str(density),
                 str(args.triangles), args.mode, args.order])
            recon = f"{folder}/recon_mesh.ply" if args.mode == "mesh" else f"{folder}/recon_points.ply"
            mask, plane = f"{folder}/ObsMask/ObsMask1_10.mat", f"{folder}/ObsMask/Plane1.mat"
            rows = []
            wall, cpu, rss, out = run([args.roving, "measure", f"{folder}/Points/stl/stl001_total.ply", recon,
                                       "--protocol", "dtu", "--dtu-obs-mask", mask, "--dtu-plane", plane,
                                       "--protocol-seed", "none", "--json", f"{folder}/report.json", "--quiet"])
            report = json.load(open(f"{folder}/report.json"))["dtu_protocol"]
            ours = [report["accuracy"], report["completeness"], report["overall"]]
            rows.append(("roving measure --protocol dtu", wall, cpu, rss, ours))
            if args.dtueval:
                script = f"{folder}/eval_in_order.py"
                source = open(os.path.join(args.dtueval, "eval.py")).read()
                assert "shuffle_rng.shuffle(data_pcd, axis=0)" in source
                open(script, "w").write(source.replace("shuffle_rng.shuffle(data_pcd, axis=0)", "pass"))
                wall, cpu, rss, out = run([sys.executable, script, "--data", recon, "--scan", "1", "--mode", args.mode,
                                           "--dataset_dir", folder, "--vis_out_dir", folder])
                theirs = [float(v) for v in out.strip().splitlines()[-1].split()]
                for name, a, b in zip(("accuracy", "completeness", "overall"), ours, theirs):
                    if abs(a - b) > 1e-9 * abs(b):
                        raise SystemExit(f"{name}: roving {a!r}, eval.py {b!r}: not the same figure; nothing timed")
                rows.append(("DTUeval-python eval.py", wall, cpu, rss, theirs))
                ratios.append((report["reconstruction_points"], rows[1][1] / rows[0][1], rows[1][3] / rows[0][3]))
        add_rows(lines, rows, report["reconstruction_points"], report["ground_truth_points"], "{:.9g}")
    name = "dtu-speed-dense-mesh.md" if args.triangles else "dtu-speed.md"
    if args.mode == "pcd" or args.order != "file":
        name = f"dtu-speed-{args.mode}-{args.order}.md"
    write_report(lines, ratios, args.out, name)


if __name__ == "__main__":
    if sys.argv[1:2] == ["--make-scene"]:
        make_scene(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5]), int(sys.argv[6]),
                   sys.argv[7], sys.argv[8])
    else:
        main()
