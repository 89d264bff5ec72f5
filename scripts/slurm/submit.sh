#!/usr/bin/env bash
# Runs a ReliefLab sweep on a Slurm cluster: a job array of N shards (sweep.sbatch), then a
# merge job that starts when every shard succeeded and writes OUT/merged (rows.csv, tables,
# Pareto fronts). Prints the two job ids; with --wait, waits for the merge and exits with its
# status.
#   scripts/slurm/submit.sh [--wait] CONFIG OUT N [RELIEFLAB] [-- SBATCH_OPTIONS...]
# RELIEFLAB defaults to build/relieflab; every path must be visible from the compute nodes.
set -euo pipefail
wait=false
if [ "${1:-}" = "--wait" ]; then wait=true; shift; fi
[ $# -ge 3 ] || { sed -n '2,8p' "$0" >&2; exit 2; }
config=$(realpath "$1") out=$(realpath -m "$2") n=$3
shift 3
relieflab=build/relieflab
if [ $# -gt 0 ] && [ "$1" != "--" ]; then relieflab=$1; shift; fi
[ "${1:-}" = "--" ] && shift
relieflab=$(realpath "$relieflab")
[ -x "$relieflab" ] || { echo "submit: no relieflab at $relieflab" >&2; exit 2; }
[[ "$n" =~ ^[1-9][0-9]*$ ]] || { echo "submit: N must be a positive number, got '$n'" >&2; exit 2; }
mkdir -p "$out/logs"
here=$(dirname "$(realpath "$0")")
array=$(sbatch --parsable --array=0-$((n - 1)) --output="$out/logs/shard-%a.log" "$@" \
  "$here/sweep.sbatch" "$config" "$out" "$relieflab")
array=${array%%;*}
shards=()
for ((i = 0; i < n; ++i)); do shards+=("$out/shard-$i"); done
merge_args=(--parsable --dependency=afterok:"$array" --kill-on-invalid-dep=yes
  --job-name=relieflab-merge
  --output="$out/logs/merge.log")
$wait && merge_args+=(--wait)
echo "submit: shards: job $array (array 0-$((n - 1))), logs in $out/logs"
merge=$(sbatch "${merge_args[@]}" "$@" --wrap "$(printf '%q ' "$relieflab" merge "$out/merged" "${shards[@]}")")
echo "submit: merge: job ${merge%%;*} -> $out/merged"
