#!/usr/bin/env bash
# Closest point end to end against CloudCompare's C2M (a step of its own, for a machine with
# CloudCompare: `apt install cloudcompare`; about 2 minutes on 2 cores): the scaling pairs
# n=8 (4.4 M / 669 k triangles) and n=12 (10 M / 1.5 M), into results/cloudcompare-c2m.md.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/datasets_gen/roving-datasets --data "${ROVING_DATA:-data}" --out build/datasets --scaling
/usr/bin/python3 bench/cloudcompare_c2m.py --roving build/roving/roving --out results "$@"
