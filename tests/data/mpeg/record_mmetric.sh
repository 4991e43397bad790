#!/usr/bin/env bash
# Records MPEG mmetric's own output (`mm compare --mode pcc`) on the pairs of make_meshes.py, the
# golden values tests/mpeg_test.cpp holds `roving measure --pcc` on meshes to. mmetric is not part of
# roving: build it from https://github.com/MPEGGroup/mpeg-pcc-mmetric (tag 1_1_7, with Debian's
# libglfw3-dev) and give its `mm` executable:
#   MMETRIC=/path/to/mm bash tests/data/mpeg/record_mmetric.sh
# Each golden file starts with the command that made it; the rest is mm's stdout as printed.
set -euo pipefail
cd "$(dirname "$0")"
: "${MMETRIC:?set MMETRIC to the mm executable of mmetric}"
mkdir -p golden
record() {  # name, A, B, more mm options
  local name=$1 a=$2 b=$3
  shift 3
  local command=(mm compare --mode pcc "--inputModelA=$a" "--inputModelB=$b" --hausdorff "$@")
  {
    echo "# ${command[*]}"
    "$MMETRIC" "${command[@]:1}"
  } > "golden/$name.txt"
}
record mmetric_fandisk10 fandisk10_a.ply fandisk10_b.ply
record mmetric_fandisk10_r1023 fandisk10_a.ply fandisk10_b.ply --resolution=1023
record mmetric_rocker8 rocker8_a.ply rocker8_b.ply
# A mesh against a point cloud: mmetric samples the mesh and passes the cloud through.
record mmetric_fandisk10_points fandisk10_a.ply fandisk10_points_b.ply
# mmetric's --normalCalcModificationEnable=false: A -> B's D2 along A's normals carried onto B, as
# pc_error carries them, instead of B's own.
record mmetric_fandisk10_carried fandisk10_a.ply fandisk10_b.ply --normalCalcModificationEnable=false
# mmetric's --neighborsProc (its pc_error's): the colour of the tied nearest points, the nearest and
# the farthest in RGB.
record mmetric_fandisk10_neighbors0 fandisk10_a.ply fandisk10_b.ply --neighborsProc=0
record mmetric_fandisk10_neighbors3 fandisk10_a.ply fandisk10_b.ply --neighborsProc=3
record mmetric_fandisk10_neighbors4 fandisk10_a.ply fandisk10_b.ply --neighborsProc=4
# mmetric's --dropDuplicates (its own removeDuplicatePoints, pc_error's with normals averaged) on
# the samples of both meshes: 0 all kept, 1 the first kept; and --neighborsProc=2, which weighs a
# merged point by how many it merged.
record mmetric_fandisk10_dropdups0 fandisk10_a.ply fandisk10_b.ply --dropDuplicates=0
record mmetric_fandisk10_dropdups1 fandisk10_a.ply fandisk10_b.ply --dropDuplicates=1
record mmetric_fandisk10_neighbors2 fandisk10_a.ply fandisk10_b.ply --neighborsProc=2
record mmetric_fandisk10_dropdups0_neighbors4 fandisk10_a.ply fandisk10_b.ply --dropDuplicates=0 --neighborsProc=4
