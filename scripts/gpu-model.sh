#!/usr/bin/env bash
# Regenerates the NVIDIA H200 cost model (configs/gpu-models/nvidia-h200.toml) and its report
# (results/gpu-model/README.md) from the committed GPU rows and op counts.
#
#   scripts/gpu-model.sh [--counts] [--check]
#
# --counts first re-measures the op counts of the GPU rows' cells on this machine's renderer
# (llvmpipe will do: the counts are the shader's, not the renderer's; about 10 minutes on 2
# cores), into results/gpu-model/counts/. The GPU rows of 2026-12-04 were measured with a
# package that predates the counters, so their counts come from these runs; rows measured since
# carry their own. --check writes nothing and fails when the model or the report differs from
# what the rows give (a ctest runs it).
set -euo pipefail
cd "$(dirname "$0")/.."
cli=${RELIEFLAB_CLI:-build/relieflab}
check=()
for arg in "$@"; do
  case "$arg" in
    --counts) counts=1 ;;
    --check) check=(--check) ;;
    *) echo "gpu-model: unknown argument '$arg' (--counts, --check)" >&2; exit 2 ;;
  esac
done

if [ -n "${counts:-}" ]; then
  mkdir -p results/gpu-model/counts
  for config in gpu-cost gpu-cost-heldout; do
    # The same cells, one frame each: only the counts are wanted.
    tmp_config=configs/gpu/.counts-$config.toml
    out=$(mktemp -d)
    trap 'rm -f "$tmp_config"; rm -rf "$out"' EXIT
    sed 's/^frames = .*/frames = 1/; s/^warmup = .*/warmup = 0/' configs/gpu/$config.toml > "$tmp_config"
    "$cli" run "$tmp_config" --out "$out" -q
    cp "$out/rows.csv" results/gpu-model/counts/$config.csv
    rm -f "$tmp_config"
    rm -rf "$out"
  done
fi

python3 scripts/fit-cost-model.py --gpu "NVIDIA H200" \
  --fit results/gpu-cost/rows.csv:results/gpu-model/counts/gpu-cost.csv \
  --fit results/gpu-cost-heldout/rows.csv:results/gpu-model/counts/gpu-cost-heldout.csv \
  --renderer-check results/gpu-model/renderer-check/gpu-warmup-h200.csv:results/gpu-model/renderer-check/gpu-warmup-llvmpipe.csv \
  --model configs/gpu-models/nvidia-h200.toml --report results/gpu-model/README.md "${check[@]}"
