#!/usr/bin/env bash
# results/apaza-gpu-sampling/rows.csv: the cell complexes of Table 1 (bunny, teapot, dragon) with
# their distance and normal maps sampled on the GPU as Section 3.3.2 does and their fragments
# counted in the stencil buffer as Section 3.3.3 does, against the CPU's per-texel projection
# lines (bench/cell_gpu_sampling.cpp), then its digest and the README's verdicts.
# About a minute and a half on 2 cores; run it on an idle machine (the times are wall clock).
#   scripts/cell-gpu-sampling-rows.sh [--meshes bunny,teapot,dragon] [--runs 3]
exec "$(dirname "$0")/study-rows.sh" cell_gpu_sampling apaza-gpu-sampling "$@"
