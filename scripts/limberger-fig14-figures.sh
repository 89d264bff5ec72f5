#!/usr/bin/env bash
# The two figures of results/limberger-fig14/ and the PSNR of its 256^2 renders against the
# 1024^2 ones, from a run of configs/papers/limberger-fig14.toml (its images stay in the run
# folder; default: the one scripts/reproduce.sh leaves):
#   scripts/reproduce.sh configs/papers/limberger-fig14.toml
#   scripts/limberger-fig14-figures.sh [RUN_DIR]
# Each figure is the run's own renders and truth images side by side (oiiotool --mosaic),
# brightened 1.8x so that the dark panel shows.
set -euo pipefail
cd "$(dirname "$0")/.."
run="${1:-out/limberger-fig14-reproduction}"
dest=results/limberger-fig14
[ -f "$run/rows.csv" ] || { echo "fig14-figures: no $run/rows.csv (run the reproduction first)" >&2; exit 2; }

# The image of one cell: SCENE TEXTURE_RES ELEVATION COLUMN (image_render or image_truth).
image() {
  python3 - "$run/rows.csv" "$@" <<'PY'
import csv, sys
rows, scene, res, el, column = sys.argv[1:]
hits = [r[column] for r in csv.DictReader(open(rows))
        if r["scene"] == scene and r["texture_res"] == res and float(r["elevation_deg"]) == float(el)]
if not hits:
    sys.exit(f"fig14-figures: no row for {scene} {res} {el}")
print(hits[0])
PY
}
at() { echo "$run/$(image "$@")"; }

oiiotool \
  "$(at plane_overview 256 50 image_render)" "$(at plane_overview 1024 50 image_render)" \
  "$(at plane_overview 1024 50 image_truth)" \
  "$(at teapot_overview 256 50 image_render)" "$(at teapot_overview 1024 50 image_render)" \
  "$(at teapot_overview 1024 50 image_truth)" \
  --mosaic 3x2 --mulc 1.8 -d uint8 -o "$dest/fig14_overview.png"
oiiotool \
  "$(at plane_closeup 256 25 image_render)" "$(at plane_closeup_d 256 25 image_render)" \
  "$(at plane_closeup 1024 25 image_render)" "$(at plane_closeup 1024 25 image_truth)" \
  "$(at teapot_closeup 256 25 image_render)" "$(at teapot_closeup_d 256 25 image_render)" \
  "$(at teapot_closeup 1024 25 image_render)" "$(at teapot_closeup 1024 25 image_truth)" \
  --mosaic 4x2 --mulc 1.8 -d uint8 -o "$dest/fig14_closeup.png"
echo "wrote $dest/fig14_overview.png and $dest/fig14_closeup.png"

# The 256^2 renders against the 1024^2 ones (not against the truth), per scene and view.
for scene in plane_overview plane_closeup teapot_overview teapot_closeup; do
  for el in 50 25; do
    psnr=$(oiiotool "$(at $scene 256 $el image_render)" "$(at $scene 1024 $el image_render)" \
             --diff 2>&1 | sed -n 's/.*Peak SNR = \([0-9.]*\).*/\1/p' | head -1 || true)
    echo "$scene at ${el} degrees: 256^2 against 1024^2 renders, PSNR ${psnr:-inf} dB"
  done
done
