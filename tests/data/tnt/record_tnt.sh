#!/usr/bin/env bash
# Records the Tanks and Temples toolbox's own figures on this folder's scene, and digests of the
# coloured viewing files it writes (tests/tnt_test.cpp holds them):
#   bash tests/data/tnt/record_tnt.sh /path/to/TanksAndTemples
# (recorded at its commit 3c2c212, 2022-10-29).
# The toolbox (github.com/isl-org/TanksAndTemples, python_toolbox/evaluation) run by Debian 12's
# python3 with python3-open3d 0.16.1, python3-matplotlib 3.6.3 and NumPy 1.24.2. run.py's last
# two steps are called as it calls them, untouched: EvaluateHisto(pcd, gt_pcd, trans, vol,
# tau / 2, tau, out_dir, 5, scene), then plot_graph with what it returned; `trans` is the scene's
# alignment file as read by np.loadtxt. registration.txt is run.py's whole run_evaluation with its
# registration (RANSAC and ICP) on the moved reconstruction; the toolbox's registration module
# needs toolbox_on_open3d_0_16.py (beside this script) on Open3D 0.16.
set -euo pipefail
toolbox="$(cd "$1/python_toolbox/evaluation" && pwd)"
here="$(cd "$(dirname "$0")" && pwd)"
out="$here/golden"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
commit="${TNT_COMMIT:-$(git -C "$1" rev-parse --short HEAD 2>/dev/null || echo unknown)}"  # TNT_COMMIT: for an archive of it
record() {  # golden file, reconstruction
  /usr/bin/python3 - "$toolbox" "$here" "$2" "$work" "$commit" >"$out/$1" <<'PY'
import sys
toolbox, here, ply, work, commit = sys.argv[1:]
sys.path.insert(0, toolbox)
import contextlib, io, os
import matplotlib
matplotlib.use("Agg")
import numpy as np
import open3d as o3d
from evaluation import EvaluateHisto
from plot import plot_graph
scene, tau = "Bench", 0.01
pcd = o3d.io.read_point_cloud(os.path.join(here, ply))
gt_pcd = o3d.io.read_point_cloud(os.path.join(here, scene + ".ply"))
trans = np.loadtxt(os.path.join(here, scene + "_trans.txt"))
vol = o3d.visualization.read_selection_polygon_volume(os.path.join(here, scene + ".json"))
with contextlib.redirect_stdout(io.StringIO()):
    p, r, f, edges_s, cum_s, edges_t, cum_t = EvaluateHisto(pcd, gt_pcd, trans, vol, tau / 2.0, tau, work, 5, scene)
    plot_graph(scene, f, tau, edges_s, cum_s, edges_t, cum_t, 5, work)
print(f"# TanksAndTemples {commit} python_toolbox/evaluation, open3d {o3d.__version__}, numpy {np.__version__}, "
      f"matplotlib {matplotlib.__version__}")
print(f"# EvaluateHisto(read_point_cloud('{ply}'), read_point_cloud('{scene}.ply'), "
      f"np.loadtxt('{scene}_trans.txt'), read_selection_polygon_volume('{scene}.json'), {tau / 2}, {tau}, out, 5, '{scene}')")
print("# precision recall fscore; the points cropped and thinned (reconstruction, then ground truth) by the same")
print("# Open3D calls; then the edges, cum_source and cum_target, one array a line, each value repr'd")
print(repr(p), repr(r), repr(f))
import copy
o3d.utility.set_verbosity_level(o3d.utility.VerbosityLevel.Error)
s = copy.deepcopy(pcd)
s.transform(trans)
s = vol.crop_point_cloud(s)
t = vol.crop_point_cloud(gt_pcd)
print(len(s.points), len(s.voxel_down_sample(tau / 2.0).points), len(t.points), len(t.voxel_down_sample(tau / 2.0).points))
for values in (edges_s, cum_s, cum_t):
    print(" ".join(repr(float(v)) for v in values))
PY
}
# The viewing files EvaluateHisto wrote for the last reconstruction recorded (write_color_distances):
# per file its point count, the sha256 of its points sorted, each as x y z (float64, little-endian)
# and red green blue (bytes), and how many points have each colour.
record_plys() {  # golden file
  /usr/bin/python3 - "$work" "$commit" >"$out/$1" <<'PY'
import hashlib, os, sys
import numpy as np
work, commit = sys.argv[1:]
print(f"# TanksAndTemples {commit} EvaluateHisto's Bench.precision.ply and Bench.recall.ply (write_color_distances,")
print("# hot_r of min(d, 3 tau) / (3 tau)); per file: points, sha256 of the records (x y z float64, r g b uint8)")
print("# sorted by x, y, z, r, g, b; then each colour's count")
types = {"double": "<f8", "float": "<f4", "uchar": "u1"}
for name in ("precision", "recall"):
    data = open(os.path.join(work, f"Bench.{name}.ply"), "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    assert "format binary_little_endian 1.0" in header
    fields = [(line.split()[2], types[line.split()[1]]) for line in header if line.startswith("property")]
    rows = np.frombuffer(data[end:], dtype=np.dtype(fields))
    records = sorted(zip(rows["x"].tolist(), rows["y"].tolist(), rows["z"].tolist(),
                         rows["red"].tolist(), rows["green"].tolist(), rows["blue"].tolist()))
    digest = hashlib.sha256()
    for x, y, z, r, g, b in records:
        digest.update(np.array([x, y, z], "<f8").tobytes() + bytes([r, g, b]))
    print(name, len(records), digest.hexdigest())
    colours, counts = np.unique(np.stack([rows["red"], rows["green"], rows["blue"]], 1), axis=0, return_counts=True)
    print(" ".join(f"{r},{g},{b}:{n}" for (r, g, b), n in zip(colours.tolist(), counts.tolist())))
PY
}
# run.py itself (run_evaluation, untouched) on the scene laid out as its dataset folder (tau 0.01 as
# Barn's, so the folder is named Barn), the moved reconstruction and its trajectory: once per seed,
# on one thread (OMP_NUM_THREADS=1: Open3D's RANSAC then draws in order from utility.random.seed).
# Its registration functions and EvaluateHisto are wrapped to record what they return.
record_registration() {  # golden file
  local scene="$work/Barn"
  mkdir -p "$scene"
  for suffix in .ply .json _trans.txt _COLMAP_SfM.log _mapping_reference.txt; do
    ln -sf "$here/Bench$suffix" "$scene/Barn$suffix"
  done
  OMP_NUM_THREADS=1 /usr/bin/python3 - "$toolbox" "$here" "$scene" "$work" "$commit" >"$out/$1" <<'PY'
import sys
toolbox, here, scene, work, commit = sys.argv[1:]
sys.path.insert(0, here)
import toolbox_on_open3d_0_16  # noqa: F401  (before the toolbox imports Open3D's registration)
sys.path.insert(0, toolbox)
import contextlib, io, os
import matplotlib
matplotlib.use("Agg")
import numpy as np
import open3d as o3d
import run
print(f"# TanksAndTemples {commit} python_toolbox/evaluation run.py, open3d {o3d.__version__}, numpy {np.__version__},")
print("# OMP_NUM_THREADS=1, through toolbox_on_open3d_0_16.py; per seed, after o3d.utility.random.seed(seed):")
print("# run_evaluation('<scene>/Barn', 'Bench_moved.log', 'Bench_moved_points.ply', out), the folder holding")
print("# Bench's files as Barn's. Lines: seed; RANSAC's transformation (16 values, row by row); then per ICP round")
print("# its fitness, inlier RMSE and the alignment after it (16 values); then precision recall fscore")
steps = []
def recorded(function):
    def call(*args, **kwargs):
        result = function(*args, **kwargs)
        steps.append(result)
        return result
    return call
run.trajectory_alignment = recorded(run.trajectory_alignment)
run.registration_vol_ds = recorded(run.registration_vol_ds)
run.registration_unif = recorded(run.registration_unif)
run.EvaluateHisto = recorded(run.EvaluateHisto)
for seed in range(1, 6):
    steps.clear()
    o3d.utility.random.seed(seed)
    with contextlib.redirect_stdout(io.StringIO()):
        run.run_evaluation(scene, os.path.join(here, "Bench_moved.log"), os.path.join(here, "Bench_moved_points.ply"),
                           os.path.join(work, "out"))
    o3d.utility.set_verbosity_level(o3d.utility.VerbosityLevel.Error)
    print(seed)
    print(" ".join(repr(float(v)) for v in np.asarray(steps[0]).ravel()))
    for r in steps[1:4]:
        print(repr(r.fitness), repr(r.inlier_rmse), " ".join(repr(float(v)) for v in np.asarray(r.transformation).ravel()))
    print(repr(steps[4][0]), repr(steps[4][1]), repr(steps[4][2]))
PY
}
record_registration registration.txt
record mesh.txt Bench_mesh.ply
record points.txt Bench_points.ply
record_plys points_plys.txt
cp "$work/PR_Bench_@d_th_0_0100.png" "$out/toolbox_curves.png"
