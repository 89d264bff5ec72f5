#pragma once
// The texture-space AO map computed by a fragment shader (harness/glsl/ao_map.frag), one
// fragment per texel: the paper's way (Limberger et al., Section IV-A). Same search and
// answers as compute_ao_map_march() up to float rounding (tests/test_ambient_occlusion.cpp checks
// it); bench/bench_precompute.cpp times both. Needs the GL context.
#include "relief/ao_map.h"
#include "scene/scene.h"

namespace rl {

AoMap compute_ao_map_gpu(const ReliefMap& map, const AoMapOptions& options);

// Who computes a scene's AO map (ambient_occlusion.map_method). Each keys the precompute cache
// by a name of its own; the line sweep keeps "cpu", the name its cached maps were written under.
AoMapMethod ao_map_method(AmbientOcclusionDesc::MapMethod method);

}  // namespace rl
