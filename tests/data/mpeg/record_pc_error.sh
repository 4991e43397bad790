#!/usr/bin/env bash
# Records MPEG pc_error's own output on the pairs of make_clouds.py, the golden values
# tests/mpeg_test.cpp holds roving's `measure --pcc` to. pc_error is not part of roving: build it
# from https://github.com/MPEGGroup/mpeg-pcc-dmetric (tag release-v0.14.2, `cmake -S source -B build
# && cmake --build build`) and give its path:
#   PC_ERROR=/path/to/pc_error bash tests/data/mpeg/record_pc_error.sh
# Each golden file starts with the command that made it; the rest is pc_error's stdout as printed.
set -euo pipefail
cd "$(dirname "$0")"
: "${PC_ERROR:?set PC_ERROR to the pc_error executable}"
mkdir -p golden
record() {  # name, A, B, pc_error options
  local name=$1 a=$2 b=$3
  shift 3
  local command=(pc_error "--fileA=$a" "--fileB=$b" "$@")
  {
    echo "# ${command[*]}"
    "$PC_ERROR" "${command[@]:1}"
  } > "golden/$name.txt"
}
record sphere10_r1023 sphere10_a.ply sphere10_b.ply --color=1 --hausdorff=1 --resolution=1023 --nbThreads=1
record sphere10_peak sphere10_a.ply sphere10_b.ply --color=1 --hausdorff=1 --nbThreads=1
record sphere10_rgb sphere10_a.ply sphere10_b.ply --color=1 --mseSpace=0 --hausdorff=1 --resolution=1023 --nbThreads=1
record torus11_r2047 torus11_a.ply torus11_b.ply --hausdorff=1 --resolution=2047 --nbThreads=1
record torus11_peak torus11_a.ply torus11_b.ply --hausdorff=1 --nbThreads=1
record blob_float_peak blob_float_a.ply blob_float_b.ply --color=1 --hausdorff=1 --nbThreads=1
record blob_float_rgb blob_float_a.ply blob_float_b.ply --color=1 --mseSpace=0 --hausdorff=1 --nbThreads=1
# A against itself: every MSE 0.
record sphere10_identical sphere10_a.ply sphere10_a.ply --color=1 --hausdorff=1 --resolution=1023 --nbThreads=1
# B against A: B has no normals, so pc_error computes no D2.
record sphere10_swapped sphere10_b.ply sphere10_a.ply --color=1 --hausdorff=1 --resolution=1023 --nbThreads=1
# A's normals from a file of their own (--inputNorm): the file's points in another order, its normals
# other than A's.
record sphere10_normals_file sphere10_a_bare.ply sphere10_b.ply --inputNorm=sphere10_a_normals.ply --color=1 --hausdorff=1 --resolution=1023 --nbThreads=1
# A's normals not unit, some of length 0: pc_error uses them as they are.
record sphere10_scaled_normals sphere10_a_scaled_normals.ply sphere10_b.ply --color=1 --hausdorff=1 --resolution=1023 --nbThreads=1
# pc_error's options that change a figure, each on sphere10 (duplicates in both clouds, ties at
# the nearest distance everywhere, colour, normals), then some together and on other clouds.
common=(--color=1 --hausdorff=1 --resolution=1023 --nbThreads=1)
record sphere10_dropdups0 sphere10_a.ply sphere10_b.ply "${common[@]}" --dropdups=0
record sphere10_dropdups1 sphere10_a.ply sphere10_b.ply "${common[@]}" --dropdups=1
record sphere10_neighbors0 sphere10_a.ply sphere10_b.ply "${common[@]}" --neighborsProc=0
record sphere10_neighbors2 sphere10_a.ply sphere10_b.ply "${common[@]}" --neighborsProc=2
record sphere10_neighbors3 sphere10_a.ply sphere10_b.ply "${common[@]}" --neighborsProc=3
record sphere10_neighbors4 sphere10_a.ply sphere10_b.ply "${common[@]}" --neighborsProc=4
record sphere10_average_normals0 sphere10_a.ply sphere10_b.ply "${common[@]}" --averageNormals=0
record sphere10_ycocg sphere10_a.ply sphere10_b.ply "${common[@]}" --mseSpace=8
record sphere10_dropdups0_neighbors2 sphere10_a.ply sphere10_b.ply "${common[@]}" --dropdups=0 --neighborsProc=2
record sphere10_mixed sphere10_a.ply sphere10_b.ply --color=1 --hausdorff=1 --nbThreads=1 --dropdups=1 --neighborsProc=4 --averageNormals=0 --mseSpace=8
record torus11_average_normals0 torus11_a.ply torus11_b.ply --hausdorff=1 --resolution=2047 --nbThreads=1 --averageNormals=0
record blob_float_neighbors3 blob_float_a.ply blob_float_b.ply --color=1 --hausdorff=1 --nbThreads=1 --neighborsProc=3 --dropdups=0
# A's normals with 60 NaN: pc_error computes on (D2 adds the coordinates' differences, unsquared).
record sphere10_nan_normals sphere10_a_nan_normals.ply sphere10_b.ply "${common[@]}"
record sphere10_nan_normals_average0 sphere10_a_nan_normals.ply sphere10_b.ply "${common[@]}" --averageNormals=0
