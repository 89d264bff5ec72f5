#!/usr/bin/env bash
# results/apaza-secondary-rays/rows.csv: primary, reflected and refracted rays through the cell
# complexes of Table 1 (bench/secondary_rays.cpp: one ray per pixel of a 512 x 512 view, timed
# on this machine's renderer, priced by the NVIDIA H200 cost model, checked against the encoded
# surface), then its digest and the README's verdicts. About two minutes on 2 cores; run it on an
# idle machine (the llvmpipe times are wall clock).
#   scripts/secondary-rays-rows.sh [--meshes bunny,teapot,dragon] [--viewport 512] [--runs 7]
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/bench/secondary_rays ] || cmake --build build -j"$(nproc)" --target secondary_rays
dest=results/apaza-secondary-rays
mkdir -p "$dest"
build/bench/secondary_rays "$@" > "$dest/rows.csv.tmp"
mv "$dest/rows.csv.tmp" "$dest/rows.csv"
python3 scripts/outputs_record.py "$dest" rows.csv
build/relieflab verify --write "$dest"
echo "$dest/rows.csv: $(($(wc -l < "$dest/rows.csv") - 1)) rows"
