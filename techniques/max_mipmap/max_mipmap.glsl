// Maximum mipmaps (Tevs, Ihrke & Seidel 2008): hierarchical ray stepping over a quadtree of
// the heightfield's highest points (harness/glsl/min_depth_quadtree.glsl, min-depth in
// ReliefLab's convention). At the finest level the ray meets the cell's surface as a straight
// profile: the chord of the bilinear patch between where the ray enters and leaves the cell
// (see README: the saddle crossings this misses are what relief_hierarchical_exact solves).
#include "harness/glsl/min_depth_quadtree.glsl"

float rl_bilerp(vec4 d, vec2 f) {
  return mix(mix(d.x, d.y, f.x), mix(d.z, d.w, f.x), f.y);
}

bool rl_cell_hit(ivec2 cell, vec2 start, vec2 dir, float z0, float t, float t_exit,
                 out float t_hit) {
  vec4 d = rl_cell_corners(cell);
  vec2 lo = vec2(cell), hi = lo + 1.0;
  // Where the ray enters the cell (before t, where the quadtree let it in).
  float t_in = 0.0;
  for (int a = 0; a < 2; a++) {
    if (dir[a] > 0.0) t_in = max(t_in, (lo[a] - start[a]) / dir[a]);
    else if (dir[a] < 0.0) t_in = max(t_in, (hi[a] - start[a]) / dir[a]);
  }
  t_in = min(t_in, t);
  // Ray depth minus the surface depth at entry and exit; the profile between is their chord.
  float g_in = z0 + t_in - rl_bilerp(d, clamp(start + dir * t_in - lo, 0.0, 1.0));
  float g_out = z0 + t_exit - rl_bilerp(d, clamp(start + dir * t_exit - lo, 0.0, 1.0));
  float span = t_exit - t_in;
  float g_t = span > 0.0 ? mix(g_in, g_out, (t - t_in) / span) : g_out;
  if (g_t >= 0.0) {
    t_hit = t;
    return true;
  }
  if (g_out < 0.0) return false;
  t_hit = max(t, t_in + span * (-g_in) / (g_out - g_in));
  return true;
}

RlHit rl_intersect(vec3 p, vec3 s) {
  float t_hit;
  bool found = rl_quadtree_search(p, s, 1.0 - p.z, t_hit);
  return rl_hit_on_ray(p, s, t_hit, found);
}
