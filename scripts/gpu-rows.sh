#!/usr/bin/env bash
# Runs configs with a relocatable package (scripts/make-package.sh) on a machine with a GPU and
# gathers their rows and logs into one archive to bring back.
#
#   scripts/gpu-rows.sh PACKAGE.tar.xz RESULT_DIR CONFIG[@WARMUP_MS] ...
#
# Each CONFIG runs into its own folder; CONFIG@MS runs it with RELIEFLAB_GPU_WARMUP_MS=MS (how
# long the GPU draws before frames are timed, gl/frame_timer.h) and names the folder after both.
# RESULT_DIR gets runs.tar.gz, rewritten as each run ends (per run <name>/: its rows.csv, run.log,
# sweep.json and console output), and machine.txt (the GPU and its driver). A run that fails is logged and the
# others go on. With GPU_ROWS_DEADLINE=S (seconds), no run starts after S seconds and a run still
# going then is stopped, so that what finished comes back inside a machine's time limit.
set -uo pipefail
[ $# -ge 3 ] || { echo "usage: gpu-rows.sh PACKAGE.tar.xz RESULT_DIR CONFIG[@MS] ..." >&2; exit 2; }
package=$(realpath "$1")
result=$(realpath -m "$2")
mkdir -p "$result"
shift 2
root=$(pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
tar -C "$work" -xJf "$package" || { echo "gpu-rows: cannot unpack $package" >&2; exit 2; }
runs="$work/runs"
mkdir -p "$runs"
{
  date -u
  nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv 2>&1
} > "$result/machine.txt"

started=$(date +%s)
deadline=${GPU_ROWS_DEADLINE:-0}
for spec in "$@"; do
  left=$(( deadline > 0 ? deadline - ($(date +%s) - started) : 86400 ))
  [ "$left" -gt 0 ] || { echo "gpu-rows: deadline reached, $spec not run"; continue; }
  config=${spec%@*}
  warmup=""
  [ "$spec" != "$config" ] && warmup=${spec##*@}
  name=$(basename "$config" .toml)${warmup:+-warmup$warmup}
  echo "gpu-rows: $name"
  start=$(date +%s)
  RELIEFLAB_GPU_WARMUP_MS=$warmup timeout "$left" "$work/relieflab/run-relieflab" run "$root/$config" \
    --out "$runs/$name" > "$runs/$name.out" 2>&1 ||
    { echo "gpu-rows: $name failed:"; tail -20 "$runs/$name.out"; }
  mkdir -p "$runs/$name"
  echo "gpu-rows: $name took $(( $(date +%s) - start )) s"
  find "$runs/$name" -mindepth 1 -maxdepth 1 \
    ! -name rows.csv ! -name outputs.json ! -name run.log ! -name sweep.json -exec rm -rf {} +
  mv "$runs/$name.out" "$runs/$name/console.txt"
  tail -3 "$runs/$name/console.txt"
  tar -C "$runs" -czf "$result/runs.tar.gz.part" . && mv "$result/runs.tar.gz.part" "$result/runs.tar.gz"
done
echo "gpu-rows: wrote $result"
