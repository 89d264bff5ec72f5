// The outputs of a scene pass: colour always; with RL_GBUFFER the G-buffer of
// harness/core/gbuffer.h (world position, normal + shadow flag, hit uv / layer / fetches, aux).
layout(location = 0) out vec4 o_color;
#ifdef RL_GBUFFER
layout(location = 1) out vec4 o_position;
layout(location = 2) out vec4 o_normal;
layout(location = 3) out vec4 o_hit;
layout(location = 4) out vec4 o_aux;
#endif

// The cost a GPU pays (harness/metrics/fragment_cost.h): in the G-buffer render every fragment
// the technique's passes shade adds itself, its texture fetches and its search iterations
// (search_cost.glsl) to five r32ui images on image units 3-7 (fragments, fetch sum, largest
// fetch count, iteration sum, largest iteration count per pixel) -- kept or discarded, so a
// missed ray costs what it walked. A technique's main ends with rl_count_fragment() and discards
// with RL_DISCARD. The timing render (no RL_GBUFFER) counts nothing. Units 3-7: a GPU may offer
// only 8 image units, and depth slicing's own passes use 0 and 1. The op-counting render
// (RL_COUNT_OPS, no RL_GBUFFER) writes what each fragment executed instead.
#include "harness/glsl/search_cost.glsl"
#ifdef RL_GBUFFER
layout(binding = 3, r32ui) uniform coherent uimage2D rl_cost_fragments;
layout(binding = 4, r32ui) uniform coherent uimage2D rl_cost_fetch_sum;
layout(binding = 5, r32ui) uniform coherent uimage2D rl_cost_fetch_max;
layout(binding = 6, r32ui) uniform coherent uimage2D rl_cost_iteration_sum;
layout(binding = 7, r32ui) uniform coherent uimage2D rl_cost_iteration_max;
void rl_count_fragment() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  imageAtomicAdd(rl_cost_fragments, px, 1u);
  imageAtomicAdd(rl_cost_fetch_sum, px, uint(rl_fetches));
  imageAtomicMax(rl_cost_fetch_max, px, uint(rl_fetches));
  imageAtomicAdd(rl_cost_iteration_sum, px, uint(rl_iterations));
  imageAtomicMax(rl_cost_iteration_max, px, uint(rl_iterations));
}
#elif defined(RL_COUNT_OPS)
void rl_count_fragment() {
  rl_write_op_counts();
}
#else
void rl_count_fragment() {}
#endif
#define RL_DISCARD        \
  {                       \
    rl_count_fragment();  \
    discard;              \
  }
