#!/usr/bin/env bash
# results/apaza-secondary-rays/rows.csv: primary, reflected and refracted rays through the cell
# complexes of Table 1 (bench/secondary_rays.cpp: one ray per pixel of a 512 x 512 view, timed
# on this machine's renderer, priced by the NVIDIA H200 cost model, checked against the encoded
# surface), then its digest and the README's verdicts. About two minutes on 2 cores; run it on an
# idle machine (the llvmpipe times are wall clock).
#   scripts/secondary-rays-rows.sh [--meshes bunny,teapot,dragon] [--viewport 512] [--runs 7]
exec "$(dirname "$0")/study-rows.sh" secondary_rays apaza-secondary-rays "$@"
