// Ray-probe pass: one fragment per ray, traced with the technique's own rl_intersect.
#include "harness/glsl/relief_common.glsl"
#include "harness/glsl/probe_io.glsl"

uniform vec2 rl_probe_depth_aspect;

void main() {
  vec4 origin, direction;
  rl_probe_ray(origin, direction);
  rl_probe_quadric = vec2(origin.w, direction.w);
  rl_depth_aspect = rl_probe_depth_aspect;
  RlHit h = rl_intersect(origin.xyz, direction.xyz);
  rl_probe_write(h.t, h.uv, h.depth, float(h.layer), h.hit, rl_fetches);
}
