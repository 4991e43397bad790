#!/usr/bin/env python3
"""The Tanks and Temples protocol, end to end: `roving measure --protocol tanks-and-temples`
against the toolbox's own EvaluateHisto, or with --registration against its whole run.py
(registration, then EvaluateHisto) from the reconstruction's camera trajectory.

Each runs in its own process from the files to the figures (wall time, CPU time and peak resident
memory from os.wait4), on the same machine, one after the other: the toolbox's EvaluateHisto and
plot_graph, called as run.py calls them after its registration (Open3D on every core), and
roving on every core with --tnt-curves. Checked before timed: precision, recall and F must be
equal. The toolbox also estimates normals and writes two coloured PLY files for viewing (part of
its time, no part of its figures); roving writes the curves' PNG, as plot_graph does.

The scene is made here, Tanks-and-Temples-sized (metres, tau 0.01): the ground truth, M points on
a sphere; the reconstruction, N points on a rippled sphere, given in its own frame with the 4 x 4
alignment that takes it onto the ground truth; the crop volume, a polygon around the sphere
whose height range cuts its cap. The toolbox is not part of roving:
https://github.com/isl-org/TanksAndTemples (Debian's python3-open3d, -matplotlib).

    /usr/bin/python3 bench/tnt_speed.py --roving build/roving/roving --toolbox /path/to/TanksAndTemples \\
        --points 3000000 30000000 --out results [--registration]

With --registration the scene also has the reference's camera trajectory (100 cameras on a ring,
in the reconstruction's frame, as COLMAP's are) and the reconstruction's own (the same cameras);
run.py is run untouched through tests/data/tnt/toolbox_on_open3d_0_16.py (Open3D 0.16's names for
its calls), on every core and unseeded, as users run it; roving runs one registration
(--protocol-runs 1). The trajectories agree exactly, so any draw of RANSAC gives the same alignment
to rounding, and the figures must again be equal before anything is timed.
"""
import argparse
import json
import os
import platform
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dtu_speed import add_rows, ordered, ordered_mesh, run, write_ply, write_report  # noqa: E402

TAU = 0.01

DRIVER = r"""
import sys
toolbox, recon, truth, trans_file, crop, out = sys.argv[1:]
sys.path.insert(0, toolbox)
import matplotlib
matplotlib.use("Agg")
import numpy as np
import open3d as o3d
from evaluation import EvaluateHisto
from plot import plot_graph
tau = %r
pcd = o3d.io.read_point_cloud(recon)
gt_pcd = o3d.io.read_point_cloud(truth)
trans = np.loadtxt(trans_file)
vol = o3d.visualization.read_selection_polygon_volume(crop)
p, r, f, edges_s, cum_s, edges_t, cum_t = EvaluateHisto(pcd, gt_pcd, trans, vol, tau / 2.0, tau, out, 5, "Scene")
plot_graph("Scene", f, tau, edges_s, cum_s, edges_t, cum_t, 5, out)
print("FIGURES", repr(p), repr(r), repr(f))
""" % TAU

# run.py's run_evaluation itself, on the scene laid out as its dataset folder (named Barn: tau 0.01),
# EvaluateHisto wrapped to print its figures in full (run.py prints 4 digits).
RUN_PY = r"""
import sys
toolbox, shim, scene, traj, recon, out = sys.argv[1:]
sys.path.insert(0, shim)
import toolbox_on_open3d_0_16  # noqa: F401
sys.path.insert(0, toolbox)
import matplotlib
matplotlib.use("Agg")
import run
figures, rounds = [], []
def recorded(*args, **kwargs):
    result = evaluate(*args, **kwargs)
    figures.append(result[:3])
    return result
def registered(function):
    def call(*args, **kwargs):
        result = function(*args, **kwargs)
        rounds.append((result.fitness, result.inlier_rmse))
        return result
    return call
evaluate, run.EvaluateHisto = run.EvaluateHisto, recorded
run.registration_vol_ds = registered(run.registration_vol_ds)
run.registration_unif = registered(run.registration_unif)
run.run_evaluation(scene, traj, recon, out)
print("ROUNDS", *(f"{f!r} {r!r}" for f, r in rounds))
print("FIGURES", *map(repr, figures[0]))
"""


def write_log(path, poses):
    with open(path, "w") as f:
        for i, pose in enumerate(poses):
            f.write(f"{i} {i + 1} {len(poses)}\n" + "\n".join(" ".join(f"{v:.12f}" for v in row) for row in pose) + "\n")


def make_trajectories(folder, radius):
    """100 cameras on a ring 1.5 radii out, in the reconstruction's frame: the reference's and its own."""
    inverse = np.linalg.inv(alignment())
    poses = []
    for a in np.arange(100) / 100 * 2 * np.pi:
        pose = np.eye(4)
        pose[:3, 3] = [1.5 * radius * np.cos(a), 1.5 * radius * np.sin(a), 0.3 * radius]
        poses.append(inverse @ pose)
    write_log(f"{folder}/Scene_COLMAP_SfM.log", poses)
    write_log(f"{folder}/recon.log", poses)


def alignment():
    angle = 0.4
    t = np.eye(4)
    t[:3, :3] = [[np.cos(angle), -np.sin(angle), 0], [np.sin(angle), np.cos(angle), 0], [0, 0, 1]]
    t[:3, 3] = [10.0, -3.0, 1.5]
    return t


def make_scene(folder, points, truth, triangles=0, order="file"):
    """The scene's files; the reconstruction's spacing about tau / 5, so that tau / 2 thins it.
    With `triangles`, both are meshes (latitude-longitude spheres) of about `triangles` and
    `truth` triangles, and `points` is ignored: the toolbox reads a mesh as its vertices. Clouds and
    meshes are written in `order` (dtu_speed.py's ordered() and ordered_mesh())."""
    if triangles:
        points = triangles // 2  # a closed mesh has about half as many vertices as triangles
    radius = float(np.sqrt(points * (TAU / 5) ** 2 / (4 * np.pi)))
    def fibonacci(n, ripple):
        i = np.arange(n) + 0.5
        z = 1 - 2 * i / n
        phi = np.pi * (3 - np.sqrt(5)) * i
        r = np.sqrt(1 - z * z)
        rr = radius + ripple * np.sin(7 * np.arccos(z)) * np.sin(5 * phi)
        return rr[:, None] * np.stack([r * np.cos(phi), r * np.sin(phi), z], 1), None
    def lat_long(n, ripple):  # 4 rings^2 triangles, poles left open
        rings = max(8, int(np.sqrt(n / 4)))
        segments = 2 * rings
        t, p = np.meshgrid(np.linspace(0, np.pi, rings + 1)[1:-1],
                           np.linspace(0, 2 * np.pi, segments, endpoint=False), indexing="ij")
        rr = radius + ripple * np.sin(7 * t) * np.sin(5 * p)
        vertices = np.stack([rr * np.sin(t) * np.cos(p), rr * np.sin(t) * np.sin(p), rr * np.cos(t)], -1).reshape(-1, 3)
        a = (np.arange(rings - 2)[:, None] * segments + np.arange(segments)[None, :]).ravel()
        b = (np.arange(rings - 2)[:, None] * segments + (np.arange(segments)[None, :] + 1) % segments).ravel()
        return vertices, np.concatenate([np.stack([a, a + segments, b], 1), np.stack([b, a + segments, b + segments], 1)])
    shape = lat_long if triangles else fibonacci
    truth_points, truth_faces = shape(truth, 0.0)
    if truth_faces is None:
        truth_points = ordered(truth_points, order, TAU)
    else:
        truth_points, truth_faces = ordered_mesh(truth_points, truth_faces, order, TAU)
    write_ply(f"{folder}/Scene.ply", truth_points, truth_faces)
    t = alignment()
    recon, faces = shape(triangles or points, 1.5 * TAU)
    if faces is None:
        recon = ordered(recon, order, TAU)
    else:
        recon, faces = ordered_mesh(recon, faces, order, TAU)
    inverse = np.linalg.inv(t)
    write_ply(f"{folder}/recon.ply", recon @ inverse[:3, :3].T + inverse[:3, 3], faces)
    np.savetxt(f"{folder}/Scene_trans.txt", t)
    side = 1.2 * radius
    crop = {"class_name": "SelectionPolygonVolume", "version_major": 1, "version_minor": 0, "orthogonal_axis": "Z",
            "axis_min": -side, "axis_max": 0.8 * radius,
            "bounding_polygon": [[-side, -side, 0], [side, -side, 0], [side, side, 0], [0, 0.5 * side, 0],
                                 [-side, side, 0]]}
    json.dump(crop, open(f"{folder}/Scene.json", "w"))
    make_trajectories(folder, radius)
    return radius


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--roving", required=True)
    parser.add_argument("--toolbox", help="a TanksAndTemples checkout; without it roving alone is timed")
    parser.add_argument("--points", type=int, nargs="+", default=[3000000],
                        help="the reconstruction's points, one scene per number")
    parser.add_argument("--truth-ratio", type=float, default=10, help="reconstruction points per ground-truth point")
    parser.add_argument("--triangles", type=int, nargs="+",
                        help="meshes instead of clouds: the reconstruction's triangles, one scene per number, against "
                             "a mesh of 1 / --truth-ratio as many (writes tnt-speed-mesh.md or tnt-registration-speed-mesh.md)")
    parser.add_argument("--out", help="a folder for tnt-speed.md (tnt-registration-speed.md); else stdout")
    parser.add_argument("--order", choices=["file", "scan", "random"], default="file",
                        help="how the files hold their points (a mesh its vertices): as made (a spiral), in scan lines, or shuffled")
    parser.add_argument("--registration", action="store_true",
                        help="run.py's registration first, from the camera trajectories (roving: one run)")
    args = parser.parse_args()
    what = "run.py (registration, then EvaluateHisto)" if args.registration else "EvaluateHisto"
    sizes = (f"--triangles {' '.join(map(str, args.triangles))} --truth-ratio {args.truth_ratio:g}" if args.triangles
             else f"--points {' '.join(map(str, args.points))}")
    scene = (f"a reconstruction mesh of T triangles in its own frame with its alignment, against a ground-truth mesh "
             f"of T / {args.truth_ratio:g}, both read as their vertices (as the toolbox reads a mesh)" if args.triangles
             else f"a reconstruction of N points in its own frame with its alignment, against a ground truth of "
                  f"N / {args.truth_ratio:g} points")
    lines = [
        f"# The Tanks and Temples protocol: roving against the toolbox's {what}",
        "",
        f"Written by `bench/tnt_speed.py {sizes}"
        f"{' --registration' if args.registration else ''}{f' --order {args.order}' if args.order != 'file' else ''}` on {platform.node()} "
        f"({os.cpu_count()} cores), {time.strftime('%Y-%m-%d')}. Each scene: {scene}, tau {TAU} m, cropped by "
        "a polygon and a height range. One run each; precision, recall and F equal before anything is timed"
        + (" (with the registration: or a few thinned points apart, as noted below the table)." if args.registration
           else "."),
        "",
        "| reconstruction | ground truth | tool | wall s | CPU s | peak RSS MiB | precision | recall | F-score |",
        "| ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    ratios, notes = [], []
    for points in args.triangles or args.points:
        truth = int(points / args.truth_ratio)
        with tempfile.TemporaryDirectory() as folder:
            # In a process of its own: a child's peak RSS counts its parent's at the fork (Linux copies
            # the high-water mark), so this process stays small while the scene's arrays are made.
            run([sys.executable, __file__, "--make-scene", folder, str(points), str(truth),
                 str(points if args.triangles else 0), args.order])
            rows = []
            registration = ["--tnt-trajectory", f"{folder}/recon.log", "--tnt-reference-trajectory",
                            f"{folder}/Scene_COLMAP_SfM.log", "--protocol-runs", "1"] if args.registration else []
            wall, cpu, rss, _ = run([args.roving, "measure", f"{folder}/Scene.ply", f"{folder}/recon.ply",
                                     "--protocol", "tanks-and-temples", "--tnt-crop", f"{folder}/Scene.json",
                                     "--tnt-alignment", f"{folder}/Scene_trans.txt", "--tnt-tau", str(TAU),
                                     "--tnt-curves", f"{folder}/curves.png", "--json", f"{folder}/report.json",
                                     "--quiet"] + registration)
            report = json.load(open(f"{folder}/report.json"))["tanks_and_temples_protocol"]
            ours = [report["precision"], report["recall"], report["fscore"]]
            rows.append(("roving measure --protocol tanks-and-temples", wall, cpu, rss, ours))
            if args.toolbox and args.registration:
                scene = f"{folder}/Barn"
                os.makedirs(scene)
                for suffix in (".ply", ".json", "_trans.txt", "_COLMAP_SfM.log"):
                    os.symlink(f"{folder}/Scene{suffix}", f"{scene}/Barn{suffix}")
                driver = f"{folder}/run_py.py"
                open(driver, "w").write(RUN_PY)
                here = os.path.dirname(os.path.abspath(__file__))
                wall, cpu, rss, out = run([sys.executable, driver, os.path.join(args.toolbox, "python_toolbox", "evaluation"),
                                           os.path.join(here, "..", "tests", "data", "tnt"), scene, f"{folder}/recon.log",
                                           f"{folder}/recon.ply", f"{folder}/out"])
            elif args.toolbox:
                driver = f"{folder}/driver.py"
                open(driver, "w").write(DRIVER)
                os.makedirs(f"{folder}/out")
                wall, cpu, rss, out = run([sys.executable, driver, os.path.join(args.toolbox, "python_toolbox", "evaluation"),
                                           f"{folder}/recon.ply", f"{folder}/Scene.ply", f"{folder}/Scene_trans.txt",
                                           f"{folder}/Scene.json", f"{folder}/out"])
            if args.toolbox:
                theirs = [float(v) for v in next(l for l in out.splitlines() if l.startswith("FIGURES")).split()[1:]]
                # run.py's RANSAC is unseeded and threaded: its matrix moves by 1e-15 from run to run,
                # which can move a point of tens of millions across a voxel's boundary in the crop and
                # down-sampling that follow. With it the figures must agree to a few points of the
                # thinned clouds (and are equal where no point moves); without it, exactly.
                counts = [report["reconstruction_thinned"], report["ground_truth_thinned"]]
                points_apart = [abs(a - b) * n for a, b, n in zip(ours, theirs, counts)]
                if ours != theirs and not (args.registration and max(points_apart) <= 5.5):
                    raise SystemExit(f"roving {ours!r}, the toolbox {theirs!r}: not the same figures; nothing timed")
                if ours != theirs:
                    notes.append(f"{report['reconstruction_points']:,} points: precision and recall "
                                 f"{points_apart[0]:.0f} and {points_apart[1]:.0f} thinned points apart "
                                 f"(of {counts[0]:,} and {counts[1]:,}), run.py's own RANSAC matrix moving a "
                                 "point across a cube's boundary (docs/reconstruction.md)")
                rows.append((f"TanksAndTemples {'run.py' if args.registration else 'EvaluateHisto'}", wall, cpu, rss,
                             theirs))
                ratios.append((report["reconstruction_points"], rows[1][1] / rows[0][1], rows[1][3] / rows[0][3]))
        add_rows(lines, rows, report["reconstruction_points"], report["ground_truth_points"],
                 "{:.8f}" if args.registration else "{:.6f}")
    lines += [""] + [f"- {note}." for note in notes] if notes else []
    name = ("tnt-registration-speed" if args.registration else "tnt-speed") + ("-mesh" if args.triangles else "")
    name += f"-{args.order}" if args.order != "file" else ""
    write_report(lines, ratios, args.out, name + ".md")


if __name__ == "__main__":
    if sys.argv[1:2] == ["--make-scene"]:
        make_scene(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5]), sys.argv[6])
    else:
        main()
