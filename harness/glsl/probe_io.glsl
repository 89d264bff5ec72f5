// The ray-probe pass's inputs and outputs (run_probe_pass and decode_probe_hits on the CPU):
// one fragment per ray, origin and direction read from two RGBA32F textures (w: the base's
// quadric A, B for ray-bending techniques); (t, u, v, fetches) written at location 0 and
// (depth, layer, hit) at location 1.
#include "harness/glsl/search_cost.glsl"

layout(binding = 2) uniform sampler2D rl_probe_origin;
layout(binding = 3) uniform sampler2D rl_probe_direction;

layout(location = 0) out vec4 o_probe_hit;
layout(location = 1) out vec4 o_probe_extra;

void rl_probe_ray(out vec4 origin, out vec4 direction) {
  ivec2 px = ivec2(gl_FragCoord.xy);
  origin = texelFetch(rl_probe_origin, px, 0);
  direction = texelFetch(rl_probe_direction, px, 0);
}

// In the op-counting form of the pass (gl/op_counting.h) it writes the ray's ops too, so that a
// probe pass laid out as a view's pixels is priced like a frame (metrics/op_cost.h).
void rl_probe_write(float t, vec2 uv, float depth, float layer, bool hit, int fetches) {
  o_probe_hit = vec4(t, uv, float(fetches));
  o_probe_extra = vec4(depth, layer, hit ? 1.0 : 0.0, 0.0);
#ifdef RL_COUNT_OPS
  rl_write_op_counts();
#endif
}
