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

// First t in [t0, t1] where the ray p + t s (s.z = 1) is at or below the bilinear surface;
// false if there is none (or the walk reached RL_MAX_CELLS).
bool rl_bilinear_walk(vec3 p, vec3 s, float t0, float t1, out float t_hit) {
  // Walk from the range's start point; t below counts from t0.
  vec3 q = vec3(p.xy + s.xy * t0, p.z + t0);
  RlWalk w = rl_walk_begin(q, s);
  vec2 size = vec2(textureSize(rl_relief, 0));
  const float t_end = t1 - t0;
  float t_enter = 0.0;
  for (int n = 0; n < RL_MAX_CELLS; n++) {
    float t_exit = min(min(w.next.x, w.next.y), t_end);
    // Corners of cell (i, j): gather at the point between texel centres i and i + 1.
    vec4 g = RL_GATHER_DEPTH((vec2(w.cell) + 1.0) / size);
    float d00 = g.w, d10 = g.z, d01 = g.x, d11 = g.y;
    float A = d10 - d00, B = d01 - d00, C = d00 - d10 - d01 + d11;
    // Solve in tau = t - t_enter with the entry point in the cell's own coordinates (both in
    // [0, 1]): no cancellation between large coordinates on long, grazing rays.
    vec2 local = w.start + w.dir * t_enter - vec2(w.cell);
    float z = q.z + t_enter;
    float qa = -C * w.dir.x * w.dir.y;
    float qb = s.z - A * w.dir.x - B * w.dir.y - C * (local.x * w.dir.y + local.y * w.dir.x);
    float qc = z - d00 - A * local.x - B * local.y - C * local.x * local.y;
    float tau = qc >= 0.0 ? 0.0 : rl_smallest_root(qa, qb, qc, 0.0, t_exit - t_enter);
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
