#!/usr/bin/env bash
# Regenerates results/default/ (tables, rows.csv, Pareto fronts and plots) from the built-in
# default sweep. Images stay in the scratch run folder (out/default-reproduction/images).
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/relieflab ] || { cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build -j"$(nproc)"; }
run=out/default-reproduction
rm -rf "$run"
./build/relieflab run --out "$run" -q
mkdir -p results/default
rm -rf results/default/plots
cp "$run"/table.md "$run"/artifacts.md "$run"/pareto.md "$run"/rows.csv results/default/
cp -r "$run"/plots results/default/
echo "results/default regenerated from $run"
