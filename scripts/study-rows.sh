#!/usr/bin/env bash
# A study folder's rows.csv from a program under bench/ that prints them, then the folder's
# digest and its README's verdicts (relieflab verify --write). What secondary-rays-rows.sh and
# cell-gpu-sampling-rows.sh run; a program that fails leaves the committed rows as they were.
#   scripts/study-rows.sh PROGRAM FOLDER [the program's options]
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 2 ] || { echo "study-rows: PROGRAM FOLDER [options]" >&2; exit 2; }
program=$1 dest=results/$2
shift 2
[ -x "build/bench/$program" ] || cmake --build build -j"$(nproc)" --target "$program"
mkdir -p "$dest"
"build/bench/$program" "$@" > "$dest/rows.csv.tmp"
mv "$dest/rows.csv.tmp" "$dest/rows.csv"
python3 scripts/outputs_record.py "$dest" rows.csv
build/relieflab verify --write "$dest"
echo "$dest/rows.csv: $(($(wc -l < "$dest/rows.csv") - 1)) rows"
