// Normal mapping: no search. The "hit" is the base surface point itself; only the shading
// normal comes from the map. The baseline of chapter 5's comparison (Figure 5.9).
#include "harness/glsl/relief_common.glsl"

RlHit rl_intersect(vec3 p, vec3 s) {
  return rl_hit_on_ray(p, s, 0.0, true);
}
