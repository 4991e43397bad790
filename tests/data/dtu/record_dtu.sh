#!/usr/bin/env bash
# Records DTUeval-python's own figures on this folder's scene (tests/dtu_test.cpp holds them):
#   bash tests/data/dtu/record_dtu.sh /path/to/DTUeval-python
# DTUeval-python (github.com/jzhangbs/DTUeval-python, eval.py at commit 45b4fec) run by Debian 12's
# python3 with python3-open3d 0.16.1, python3-sklearn 1.2.1, python3-scipy 1.10.1, python3-tqdm.
# Its one line of randomness, `shuffle_rng = np.random.default_rng()` before the radius thinning,
# is the only line changed, in a copy: removed (the points' own order: deterministic), or seeded
# (np.random.default_rng(SEED)) for the seed-to-seed spread. Nothing else is touched.
set -euo pipefail
eval_py="$1/eval.py"
here="$(cd "$(dirname "$0")" && pwd)"
out="$here/golden"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
sed '/shuffle_rng.shuffle(data_pcd, axis=0)/d' "$eval_py" >"$work/eval_in_order.py"
sed 's/shuffle_rng = np.random.default_rng()/shuffle_rng = np.random.default_rng(int(__import__("os").environ["DTU_SEED"]))/' \
  "$eval_py" >"$work/eval_seeded.py"
grep -q DTU_SEED "$work/eval_seeded.py"
commit="$(git -C "$1" rev-parse --short HEAD 2>/dev/null || echo 45b4fec)"
run() {  # golden file, script, mode, data
  local file="$out/$1" cmd="/usr/bin/python3 eval.py --data $4 --scan 1 --mode $3 --dataset_dir tests/data/dtu --vis_out_dir /tmp"
  {
    echo "# DTUeval-python $commit ($2), $(/usr/bin/python3 -c 'import open3d, sklearn, scipy, numpy; print("open3d", open3d.__version__, "sklearn", sklearn.__version__, "scipy", scipy.__version__, "numpy", numpy.__version__)')"
    echo "# $cmd"
    echo "# printed: mean_d2s mean_s2d over_all"
  } >"$file"
  (cd "$here/../../.." && /usr/bin/python3 "$work/$2" --data "tests/data/dtu/$4" --scan 1 --mode "$3" \
     --dataset_dir tests/data/dtu --vis_out_dir "$work" 2>/dev/null) >>"$file"
}
run mesh_in_order.txt eval_in_order.py mesh scan1_mesh.ply
run points_in_order.txt eval_in_order.py pcd scan1_points.ply
# The shuffled protocol: 20 seeds, one line each.
for mode in mesh points; do
  file="$out/${mode}_seeds.txt"
  data="scan1_$mode.ply"; m="$mode"; [ "$mode" = points ] && m=pcd
  echo "# DTUeval-python $commit, np.random.default_rng(SEED) for SEED in 1..20: --data $data --mode $m" >"$file"
  echo "# SEED mean_d2s mean_s2d over_all" >>"$file"
  for seed in $(seq 1 20); do
    line="$(cd "$here/../../.." && DTU_SEED=$seed /usr/bin/python3 "$work/eval_seeded.py" --data "tests/data/dtu/$data" \
       --scan 1 --mode "$m" --dataset_dir tests/data/dtu --vis_out_dir "$work" 2>/dev/null)"
    echo "$seed $line" >>"$file"
  done
done
