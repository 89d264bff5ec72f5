// Ray-probe pass: one fragment per ray, read from two RGBA32F textures, traced with the
// technique's own rl_intersect. Outputs (t, u, v, fetches) and (depth, layer, hit).
#include "harness/glsl/relief_common.glsl"

layout(binding = 2) uniform sampler2D rl_probe_origin;
layout(binding = 3) uniform sampler2D rl_probe_direction;
uniform vec2 rl_probe_depth_aspect;

layout(location = 0) out vec4 o_probe_hit;
layout(location = 1) out vec4 o_probe_extra;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 origin_q = texelFetch(rl_probe_origin, px, 0);
  vec4 direction_q = texelFetch(rl_probe_direction, px, 0);
  vec3 origin = origin_q.xyz, direction = direction_q.xyz;
  rl_probe_quadric = vec2(origin_q.w, direction_q.w);
  rl_depth_aspect = rl_probe_depth_aspect;
  RlHit h = rl_intersect(origin, direction);
  o_probe_hit = vec4(h.t, h.uv, float(rl_fetches));
  o_probe_extra = vec4(h.depth, float(h.layer), h.hit ? 1.0 : 0.0, 0.0);
}
