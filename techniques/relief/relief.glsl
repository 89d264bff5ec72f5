// Relief mapping: linear search for the first point inside the relief, then binary search
// around it. Book chapter 5, 'Relief Texture mapping', Listing 5.3 (ray_intersect_rm) and
// Listing 5.4; Policarpo, Oliveira & Comba 2005.
//
// Like Listing 5.3, the linear search takes RL_LINEAR_STEPS - 1 fetches at depths
// size, 2 size, ... and, if nothing is found, keeps depth 1 (the bottom), where every ray is
// inside. It exits early (the "Pixel Shader 3.0" optimisation of the chapter). The binary
// search then halves the interval RL_BINARY_STEPS times and keeps the last inside point.
// Starting depth p.z may be > 0 (the self-shadow ray enters at the top, p.z = 0, too).
#include "harness/glsl/relief_common.glsl"

RlHit rl_intersect(vec3 p, vec3 s) {
  const int linear_steps = RL_LINEAR_STEPS;
  const int binary_steps = RL_BINARY_STEPS;
  float size = (1.0 - p.z) / float(linear_steps);
  float t = 0.0;
  float best = 1.0 - p.z;  // no inside point found: the bottom
  for (int i = 0; i < linear_steps - 1; i++) {
    RL_ITERATE;
    t += size;
    if (p.z + t >= rl_relief_depth(p.xy + s.xy * t)) {
      best = t;
      break;
    }
  }
  t = best;
  for (int i = 0; i < binary_steps; i++) {
    RL_ITERATE;
    size *= 0.5;
    if (p.z + t >= rl_relief_depth(p.xy + s.xy * t)) {
      best = t;
      t -= 2.0 * size;
    }
    t += size;
  }
  return rl_hit_on_ray(p, s, best, true);
}
