// Relaxed cone step mapping: Policarpo & Oliveira, GPU Gems 3 chapter 18 (with RL_CONSERVATIVE,
// Dummer 2006's cone step mapping on conservative cones). Each step reads the depth and cone
// ratio under the ray and advances the ray to where it leaves that texel's cone; relaxed cones
// may let a step end inside the surface, after crossing it once, so a binary search over the
// last step finds the crossing.
#include "harness/glsl/relief_common.glsl"

// RG32F: depth (as the relief's alpha) and cone ratio (texels across per unit depth / the
// longer side), GL_LINEAR + GL_REPEAT like the relief map.
layout(binding = 4) uniform sampler2D rl_cone;
#define RL_FETCH_CONE(uv) (rl_fetches++, textureLod(rl_cone, uv, 0.0).rg)

RlHit rl_intersect(vec3 p, vec3 s) {
  const float t_end = 1.0 - p.z;
  // Across per unit depth along the ray, in the cone map's unit: texels / the longer side.
  const vec2 size = vec2(textureSize(rl_cone, 0));
  const float across = length(s.xy * size) / max(size.x, size.y);
  float t = 0.0, t_prev = 0.0;
  bool reached = false;
  for (int i = 0; i < RL_CONE_STEPS; i++) {
    RL_ITERATE;
    vec2 cone = RL_FETCH_CONE(p.xy + s.xy * t);
    float gap = cone.x - (p.z + t);  // surface depth below the ray's point
    if (gap <= 0.0) {                // in or on the surface
      reached = true;
      break;
    }
    t_prev = t;
    // The cone's side at this point: across * dt = ratio * (gap - dt). A vertical ray goes
    // straight down to the surface.
    t = min(t + (across > 0.0 ? cone.y * gap / (across + cone.y) : gap), t_end);
  }
#ifdef RL_EMPTY_FLOOR
  // Over an empty floor, a ray whose steps ran out above the surface while still taking steps
  // longer than a texel is taken as one heading for the floor (nothing is drawn) rather than
  // drawn where it stopped in mid-air; one crawling in steps under a texel is at a surface.
  if (!reached && across * (t - t_prev) * max(size.x, size.y) > 1.0)
    return rl_hit_on_ray(p, s, t, false);
#endif
  // The crossing lies in the last step [t_prev, t] (or, if the steps ran out above the surface,
  // the search converges to t: the ray stops short, as the published method does).
  float lo = t_prev, hi = t;
  for (int i = 0; i < RL_BINARY_STEPS; i++) {
    RL_ITERATE;
    float mid = 0.5 * (lo + hi);
    if (p.z + mid >= RL_FETCH(rl_relief, p.xy + s.xy * mid).a) hi = mid;
    else lo = mid;
  }
  return rl_hit_on_ray(p, s, hi, true);
}
