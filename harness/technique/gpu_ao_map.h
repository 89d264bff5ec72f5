#pragma once
// The texture-space AO map computed by a fragment shader (harness/glsl/ao_map.frag), one
// fragment per texel: the paper's way (Limberger et al., Section IV-A). Same search and
// answers as compute_ao_map_march() up to float rounding (tests/test_ambient_occlusion.cpp checks
// it); bench/bench_precompute.cpp times both. Needs the GL context.
#include "relief/ao_map.h"

namespace rl {

AoMap compute_ao_map_gpu(const ReliefMap& map, const AoMapOptions& options);

}  // namespace rl
