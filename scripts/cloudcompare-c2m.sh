#!/usr/bin/env bash
# Closest point end to end against CloudCompare's C2M (a step of its own, for a machine with
# CloudCompare: `apt install cloudcompare`; about 20 minutes on 2 cores): the scaling pairs n=8
# (4.4 M / 669 k triangles) and n=12 (10 M / 1.5 M), and the streaming benchmark's 10^8-triangle REF
# against the same TEST, into results/cloudcompare-c2m.md.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/datasets_gen/roving-datasets --data "${ROVING_DATA:-data}" --out build/datasets --scaling
large=build/datasets-streaming/scaling-large/ref-n38.ply  # bench/streaming.py's, made there when missing
[ -e "$large" ] || ./build/datasets_gen/roving-datasets --data "${ROVING_DATA:-data}" --out build/datasets-streaming --scaling-large
pairs=()
for n in 8 12; do pairs+=(--pair "build/datasets/scaling/ref-n$n.ply" "build/datasets/scaling/test-n$n.ply"); done
pairs+=(--pair "$large" build/datasets/scaling/test-n12.ply)
/usr/bin/python3 bench/cloudcompare_c2m.py --roving build/roving/roving --out results "${pairs[@]}" "$@"
