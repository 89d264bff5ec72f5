// Exact first intersection of a ray with the bilinear heightfield over a range of t: the
// centerline walk of centerline_walk.glsl with, in every cell, the ray solved exactly
// against the cell's bilinear patch. Along the ray the patch depth
//   D = d00 + A fx + B fy + C fx fy,  fx, fy linear in t,
// is quadratic in t, so (ray depth - D) has at most two roots per cell; the first in the
// cell's interval is the hit. Shared by relief_exact_bilinear (the whole ray) and
// relief_robust (its exact zero-radius fallback over one column).
#include "harness/glsl/centerline_walk.glsl"

// One textureGather of the depth channel reads a patch's four corners.
#define RL_GATHER_DEPTH(uv) (rl_fetches++, textureGather(rl_relief, uv, 3))

// Smallest root of a t^2 + b t + c in [lo, hi], or -1. Stable form (Numerical Recipes 5.6).
float rl_smallest_root(float a, float b, float c, float lo, float hi) {
  float scale = max(max(abs(a), abs(b)), max(abs(c), 1e-30));
  if (abs(a) <= 1e-7 * scale) {
    if (b == 0.0) return -1.0;
    float r = -c / b;
    return (r >= lo && r <= hi) ? r : -1.0;
  }
  float disc = b * b - 4.0 * a * c;
  if (disc < 0.0) {
    if (disc < -1e-6 * b * b) return -1.0;
    disc = 0.0;  // tangency lost to rounding
  }
  float q = -0.5 * (b + (b >= 0.0 ? sqrt(disc) : -sqrt(disc)));
  float r1 = q / a;
  float r2 = q != 0.0 ? c / q : r1;
  float lo_r = min(r1, r2), hi_r = max(r1, r2);
  if (lo_r >= lo && lo_r <= hi) return lo_r;
  if (hi_r >= lo && hi_r <= hi) return hi_r;
  return -1.0;
}

// Corner depths (d00, d10, d01, d11) of a cell, one gather at its point uv = (cell + 1) / the
// map's size: between texel centres i, i + 1 and j, j + 1 for cell (i, j).
vec4 rl_cell_corners_at(vec2 uv) {
  vec4 g = RL_GATHER_DEPTH(uv);
  return vec4(g.w, g.z, g.x, g.y);
}

// The same for cell (i, j) given by its integer indices.
vec4 rl_cell_corners(ivec2 cell) {
  return rl_cell_corners_at((vec2(cell) + 1.0) / vec2(textureSize(rl_relief, 0)));
}

// First tau in [0, tau_max] at which a ray meets a cell's patch, or -1. The ray is at `local`
// (the cell's own coordinates, both in [0, 1]: no cancellation between large coordinates on
// long, grazing rays) and depth z at tau = 0, and moves by dir (texel units) and by 1 in depth
// per unit tau.
// (ray depth - patch depth) = a tau^2 + b tau + c, as vec3(a, b, c).
vec3 rl_patch_quadratic(vec4 corners, vec2 local, vec2 dir, float z) {
  float d00 = corners.x, d10 = corners.y, d01 = corners.z, d11 = corners.w;
  float A = d10 - d00, B = d01 - d00, C = d00 - d10 - d01 + d11;
  return vec3(-C * dir.x * dir.y,
              1.0 - A * dir.x - B * dir.y - C * (local.x * dir.y + local.y * dir.x),
              z - d00 - A * local.x - B * local.y - C * local.x * local.y);
}

float rl_patch_first_hit(vec4 corners, vec2 local, vec2 dir, float z, float tau_max) {
  vec3 q = rl_patch_quadratic(corners, local, dir, z);
  return q.z >= 0.0 ? 0.0 : rl_smallest_root(q.x, q.y, q.z, 0.0, tau_max);
}

// First t in [t0, t1] where the ray p + t s (s.z = 1) is at or below the bilinear surface;
// false if there is none (or the walk reached RL_MAX_CELLS).
bool rl_bilinear_walk(vec3 p, vec3 s, float t0, float t1, out float t_hit) {
  // Walk from the range's start point; t below counts from t0.
  vec3 q = vec3(p.xy + s.xy * t0, p.z + t0);
  RlWalk w = rl_walk_begin(q, s);
  const float t_end = t1 - t0;
  float t_enter = 0.0;
  for (int n = 0; n < RL_MAX_CELLS; n++) {
    RL_ITERATE;
    float t_exit = min(min(w.next.x, w.next.y), t_end);
    vec2 local = w.start + w.dir * t_enter - vec2(w.cell);
    float tau = rl_patch_first_hit(rl_cell_corners(w.cell), local, w.dir, q.z + t_enter,
                                   t_exit - t_enter);
    if (tau >= 0.0) {
      t_hit = t0 + t_enter + tau;
      return true;
    }
    if (t_exit >= t_end) break;
    t_enter = rl_walk_advance(w);
  }
  t_hit = t1;
  return false;
}
