// Parallax occlusion mapping (Tatarchuk 2006): a linear search whose sample count is
// interpolated between RL_MIN_SAMPLES (view along the normal) and RL_MAX_SAMPLES (grazing) by
// the cosine of the view angle, then the hit as the crossing of the view ray with the
// straight segment between the last two depth samples (no binary search).
#include "harness/glsl/relief_common.glsl"

RlHit rl_intersect(vec3 p, vec3 s) {
  // Unit tangent-space view z from the texture-space step s (s.z = 1 depth unit).
  vec2 world_xy = s.xy / rl_depth_aspect;
  float view_z = inversesqrt(1.0 + dot(world_xy, world_xy));
  int samples = int(mix(float(RL_MAX_SAMPLES), float(RL_MIN_SAMPLES), clamp(view_z, 0.0, 1.0)));
  samples = clamp(samples, RL_MIN_SAMPLES, RL_MAX_SAMPLES);
  float size = (1.0 - p.z) / float(samples);
  // gap(t) = map depth - ray depth: positive while the ray is above the surface.
  float gap_prev = rl_relief_depth(p.xy) - p.z;
  float t_prev = 0.0;
  for (int i = 1; i <= RL_MAX_SAMPLES; i++) {
    RL_ITERATE;
    if (i > samples) break;
    float t = size * float(i);
    float gap = rl_relief_depth(p.xy + s.xy * t) - (p.z + t);
    if (gap <= 0.0) {
      // The ray crosses the segment between the two samples where the gaps meet zero.
      float w = gap_prev > 0.0 ? gap_prev / (gap_prev - gap) : 0.0;
      return rl_hit_on_ray(p, s, mix(t_prev, t, w), true);
    }
    gap_prev = gap;
    t_prev = t;
  }
  return rl_hit_on_ray(p, s, 1.0 - p.z, true);  // the bottom, inside everywhere
}
