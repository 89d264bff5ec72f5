#!/usr/bin/env bash
# results/truth-accuracy/rows.csv from its two tables, so its verdicts are claims checked by
# `relieflab verify` like every other folder's: before.md (the tessellated truth, the
# truth_accuracy bench built at commit 4d39d25) and after.md (the exact truth, the bench now),
# one row per map, size and elevation, `truth` naming which (kind "accuracy"); and timing.md,
# build and trace times measured with both builds back to back on an idle machine (kind "timing").
#   build/bench/truth_accuracy > results/truth-accuracy/after.md && scripts/truth-accuracy-rows.sh
set -euo pipefail
cd "$(dirname "$0")/../results/truth-accuracy"
{
  echo "kind,truth,map,size,elevation_deg,k,bound_depth,build_ms,trace_ms,covered_px,hit_miss_differ,over_001_texel_pct,over_05_texel_pct,over_1_texel_pct,p99_texels,max_texels,run"
  for truth in before after; do
    # Table rows only (not the header or the |---| rule): cells trimmed, % signs dropped.
    awk -v truth="$truth" -F'|' 'NR > 2 && NF > 2 {
      line = "accuracy," truth
      for (i = 2; i < NF; i++) { c = $i; gsub(/^ +| +$|%/, "", c); line = line "," c }
      print line ","
    }' "$truth.md"
  done
  # timing.md: | truth | map | size | elevation | run | build ms | trace ms |
  awk -F'|' 'NR > 2 && NF > 2 {
    for (i = 2; i < NF; i++) { c[i] = $i; gsub(/^ +| +$/, "", c[i]) }
    print "timing," c[2] "," c[3] "," c[4] "," c[5] ",,," c[7] "," c[8] ",,,,,,,," c[6]
  }' timing.md
} > rows.csv.tmp
mv rows.csv.tmp rows.csv
python3 ../../scripts/outputs_record.py . rows.csv
echo "results/truth-accuracy/rows.csv: $(($(wc -l < rows.csv) - 1)) rows"
