// Interval mapping (Risser, Shah & Pattanaik 2005): the linear search of relief mapping
// brackets the first crossing between the last sample above the surface and the first one
// inside; RL_SECANT_STEPS iterations of regula falsi then narrow the bracket, each keeping the
// end on its side of the surface, and the hit is the secant crossing of the final bracket.
// Where relief mapping halves the bracket per fetch, the secant converges faster on smooth
// surfaces (but can stall on one end where the surface curves).
#include "harness/glsl/relief_common.glsl"

RlHit rl_intersect(vec3 p, vec3 s) {
  // gap(t) = map depth - ray depth: positive while the ray is above the surface.
  float t_above = 0.0;
  float gap_above = rl_relief_depth(p.xy) - p.z;
  if (gap_above <= 0.0) return rl_hit_on_ray(p, s, 0.0, true);  // starts inside
  float size = (1.0 - p.z) / float(RL_LINEAR_STEPS);
  float t_inside = 1.0 - p.z;  // the bottom, inside everywhere
  float gap_inside = 0.0;
  bool found = false;
  for (int i = 1; i < RL_LINEAR_STEPS; i++) {
    RL_ITERATE;
    float t = size * float(i);
    float gap = rl_relief_depth(p.xy + s.xy * t) - (p.z + t);
    if (gap <= 0.0) {
      t_inside = t;
      gap_inside = gap;
      found = true;
      break;
    }
    t_above = t;
    gap_above = gap;
  }
  if (!found) gap_inside = rl_relief_depth(p.xy + s.xy * t_inside) - (p.z + t_inside);
  for (int i = 0; i < RL_SECANT_STEPS; i++) {
    RL_ITERATE;
    float t = mix(t_above, t_inside, gap_above / max(gap_above - gap_inside, 1e-20));
    float gap = rl_relief_depth(p.xy + s.xy * t) - (p.z + t);
    if (gap <= 0.0) {
      t_inside = t;
      gap_inside = gap;
    } else {
      t_above = t;
      gap_above = gap;
    }
  }
  float w = gap_above / max(gap_above - gap_inside, 1e-20);
  return rl_hit_on_ray(p, s, mix(t_above, t_inside, w), true);
}
