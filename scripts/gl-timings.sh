#!/usr/bin/env bash
# The GL methods timed on this machine's GL beside Embree, answers checked first
# (bench/gl_timings.py): by default on llvmpipe (OSMesa) into results/gpu-cameras.md, about 2
# minutes on 2 cores. On a machine with a GPU:
#   bash scripts/gl-timings.sh --backends egl,osmesa --large --out results/gpu.md
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
for only in --quick --scaling; do  # the bunny's pairs, then the scaling pairs
  ./build/datasets_gen/roving-datasets --data "${ROVING_DATA:-data}" --out build/datasets "$only"
done
out=results/gpu-cameras.md
backends=osmesa
args=()
while (($#)); do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    --backends) backends="$2"; shift 2 ;;
    *) args+=("$1"); shift ;;
  esac
done
/usr/bin/python3 bench/gl_timings.py --roving build/roving/roving --data build/datasets --backends "$backends" \
  --out "$out" "${args[@]}"
