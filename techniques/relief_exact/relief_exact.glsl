// Exact texel traversal: Baboud & Decoret 2006, Section 3.3 ("Rasterization-based
// intersection"). The ray is walked from one centerline crossing to the next (2D
// Amanatides & Woo); at each crossing the heightfield is sampled (on a centerline bilinear
// filtering is linear, so one fetch is exact there) and compared with the ray. Between two
// crossings the heightfield is assumed linear along the ray, so the hit is where the two
// linear profiles meet. That assumption is the method's one inexactness: inside a cell the
// bilinear surface is curved along the ray and a saddle can be missed (the paper's Figure 3).
#include "harness/glsl/centerline_walk.glsl"

RlHit rl_intersect(vec3 p, vec3 s) {
  const float t_end = 1.0 - p.z;  // the ray reaches depth 1
  RlWalk w = rl_walk_begin(p, s);
  // g = surface depth - ray depth: > 0 above the surface.
  float t_prev = 0.0;
  float g_prev = RL_FETCH(rl_relief, p.xy).a - p.z;
  if (g_prev <= 0.0) return rl_hit_on_ray(p, s, 0.0, true);
  for (int n = 0; n < RL_MAX_CELLS; n++) {
    RL_ITERATE;
    float t = min(min(w.next.x, w.next.y), t_end);
    float g = RL_FETCH(rl_relief, rl_walk_uv(w, w.start + w.dir * t)).a - (p.z + t);
    if (g <= 0.0) {
      // Crossed between t_prev and t: intersect the two linear profiles.
      float t_hit = t_prev + (t - t_prev) * g_prev / (g_prev - g);
      return rl_hit_on_ray(p, s, t_hit, true);
    }
    if (t >= t_end) break;
    t_prev = t;
    g_prev = g;
    rl_walk_advance(w);
  }
  // Only a ray stopped by RL_MAX_CELLS gets here (depth 1 is inside everywhere).
  return rl_hit_on_ray(p, s, t_end, false);
}
