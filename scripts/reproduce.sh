#!/usr/bin/env bash
# Regenerates one committed reproduction: runs CONFIG from an empty folder and copies its
# tables (Markdown and LaTeX), rows.csv, Pareto fronts, plots and HTML report into
# results/<sweep name>/ (images stay in the scratch run folder,
# out/<sweep name>-reproduction/images; the report names the pictures it cannot find).
# With --images the run's images come along too (for figure reproductions with few cells).
#   scripts/reproduce.sh                                        # the built-in default sweep
#   scripts/reproduce.sh configs/papers/baboud2006-table1.toml
#   scripts/reproduce.sh --images configs/papers/baboud2006-fig11.toml
set -euo pipefail
cd "$(dirname "$0")/.."
images=false
if [ "${1:-}" = "--images" ]; then images=true; shift; fi
config="${1:-configs/default.toml}"
[ -f "$config" ] || { echo "reproduce: no such config: $config" >&2; exit 2; }
[ -x build/relieflab ] || { cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build -j"$(nproc)"; }
name=$(sed -n 's/^name *= *"\([^"]*\)".*/\1/p' "$config" | head -1)
[ -n "$name" ] || { echo "reproduce: $config has no [sweep] name" >&2; exit 2; }
run="out/$name-reproduction"
rm -rf "$run"
# A fresh precompute cache, so the precompute_ms columns measure the precompute.
export RELIEFLAB_CACHE_DIR="$run/precompute-cache"
./build/relieflab run "$config" --out "$run" -q
dest="results/$name"
mkdir -p "$dest"
rm -rf "$dest/plots"
cp "$run"/*.md "$run"/rows.csv "$run"/outputs.json "$dest/"
# LaTeX tables (format = "latex"), where the config asks for them.
for tex in "$run"/*.tex; do [ -e "$tex" ] && cp "$tex" "$dest/"; done
# The HTML report (its pictures are those of images/, so complete with --images). The results
# tree keeps one copy of its style and scripts (results/report_assets/), which every folder's
# report loads.
cp "$run"/report.html "$dest/" && rm -rf "$dest/report_assets"
mkdir -p results/report_assets
for asset in report.css report.js d3.min.js; do
  [ -f "$run/report_assets/$asset" ] || continue
  cp "$run/report_assets/$asset" results/report_assets/
  sed -i "s|\"report_assets/$asset\"|\"../report_assets/$asset\"|" "$dest/report.html"
done
cp -r "$run"/plots "$dest/"
cp "$run"/run.log "$dest/run.log"
if $images; then rm -rf "$dest/images" && cp -r "$run"/images "$dest/"; fi
# Verdicts kept as claims: the README's section and the report's panel, from the new rows.
if [ -f "$dest/claims.toml" ]; then ./build/relieflab verify --write "$dest" || true; fi
echo "$dest regenerated from $run"
