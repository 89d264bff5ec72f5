// Window-pyramid exact search (ReliefLab, beyond the published work): empty-space skipping with
// float arithmetic only. Level k of rl_window holds, per texel of a 2^k-texel block, the least
// depth of every bilinear cell that a step of 2^k texels from anywhere in the block can reach,
// one layer per quadrant of the ray's direction (harness/relief/window_pyramid.h). So from any
// point one fetch tells whether the ray may advance 2^k texels along its faster axis: if its
// depth at the step's end is still above that bound, nothing in reach can be hit, and if not, it
// is still above it down to the bound's depth. No node alignment, no integer cell arithmetic: a
// step succeeds and the search climbs a level, or fails and it descends; where even a one-texel
// step may hit, the cells of the next RL_SOLVE_TEXELS texels of the ray are solved exactly, as
// relief_exact_bilinear solves every cell it walks.
#include "harness/glsl/bilinear_walk.glsl"

// R32F mip chains, nearest; layer = the ray's way along x (1 if negative) + 2 x its way along y,
// or one layer for any way (RL_WINDOWS_BY_WAY 0).
layout(binding = 4) uniform sampler2DArray rl_window;
uniform float rl_window_top;  // their coarsest level

// Hard cap on steps per ray: loops stay bounded whatever the view (a ray that reaches it
// reports no hit). Each step advances, or descends a level that a later step climbed.
#define RL_WINDOW_MAX_STEPS (4 * RL_MAX_CELLS)

// Cells a stretch of RL_SOLVE_TEXELS texels along the faster axis crosses: at most 2 per
// texel, and 1 more, with room for rounding.
#define RL_SOLVE_CELLS (3 * RL_SOLVE_TEXELS + 1)
#define RL_FETCH_WINDOW(uv, layer, lod) (rl_fetches++, textureLod(rl_window, vec3(uv, layer), lod).r)

// The ray in texel-centre coordinates (centerline_walk.glsl's frame, set up once per ray):
// X(t) = start + dir t, cell c spans [c, c + 1] per axis; per axis the t between crossings
// (delta), which way cells advance (+1 or -1) and how far a crossing lies ahead of a cell's
// low side (1 moving up, 0 moving down).
struct RlCellRay {
  vec2 start, dir, delta, advance, ahead;
  vec2 texel;  // 1 / the map's size: a cell's gather point is (cell + 1) texel
};

RlCellRay rl_cell_ray(vec3 p, vec3 s) {
  RlCellRay r;
  r.start = fract(p.xy) * vec2(textureSize(rl_relief, 0)) - 0.5;
  r.dir = s.xy * vec2(textureSize(rl_relief, 0));
  r.delta = 1.0 / max(abs(r.dir), vec2(1e-30));
  r.advance = mix(vec2(-1.0), vec2(1.0), greaterThanEqual(r.dir, vec2(0.0)));
  r.ahead = max(r.advance, vec2(0.0));
  r.texel = 1.0 / vec2(textureSize(rl_relief, 0));
  return r;
}

// rl_patch_first_hit with the common case first: a ray above the patch at both ends of its
// interval meets it only where (ray depth - patch depth) peaks inside the interval at or above
// zero, which takes no root to rule out. Only then, or where the ray ends at or below the
// patch, are the roots solved -- by rl_smallest_root, so a hit is the exact walk's.
float rl_window_patch_hit(vec4 corners, vec2 local, vec2 dir, float z, float tau_max) {
  vec3 q = rl_patch_quadratic(corners, local, dir, z);
  if (q.z >= 0.0) return 0.0;
  bool ends_below = (q.x * tau_max + q.y) * tau_max + q.z >= 0.0;
  bool may_peak = q.x < 0.0 && q.y > 0.0 && q.y < -2.0 * q.x * tau_max &&
                  q.y * q.y - 4.0 * q.x * q.z >= -1e-6 * q.y * q.y;
  return ends_below || may_peak ? rl_smallest_root(q.x, q.y, q.z, 0.0, tau_max) : -1.0;
}

// The first hit on the cells the ray crosses between t0 and t1 (at most RL_SOLVE_TEXELS texels
// of travel), each solved exactly unless the ray's depth at the cell's exit is still above all
// four corners. Else false, with the t it got to.
bool rl_solve_cells(RlCellRay r, float z0, float t0, float t1, out float t_out) {
  vec2 cell = floor(r.start + r.dir * t0);
  vec2 next = t0 + (cell + r.ahead - (r.start + r.dir * t0)) * r.advance * r.delta;
  float t_enter = t0;
  for (int n = 0; n < RL_SOLVE_CELLS; n++) {
    RL_ITERATE;
    float t_exit = min(min(next.x, next.y), t1);
    vec4 corners = rl_cell_corners_at((cell + 1.0) * r.texel);
    if (z0 + t_exit >= min(min(corners.x, corners.y), min(corners.z, corners.w))) {
      vec2 local = r.start + r.dir * t_enter - cell;
      float tau = rl_window_patch_hit(corners, local, r.dir, z0 + t_enter, t_exit - t_enter);
      if (tau >= 0.0) {
        t_out = t_enter + tau;
        return true;
      }
    }
    t_enter = t_exit;
    if (t_exit >= t1) break;
    bool along_x = next.x <= next.y;
    cell += along_x ? vec2(r.advance.x, 0.0) : vec2(0.0, r.advance.y);
    next += along_x ? vec2(r.delta.x, 0.0) : vec2(0.0, r.delta.y);
  }
  t_out = t_enter;
  return false;
}

RlHit rl_intersect(vec3 p, vec3 s) {
  const float t_end = 1.0 - p.z;  // the ray reaches depth 1, inside everywhere
  RlCellRay ray = rl_cell_ray(p, s);
  // Ray parameter per texel of travel along the faster axis.
  float t_texel = min(ray.delta.x, ray.delta.y);
  float lod = min(float(RL_START_LEVEL), rl_window_top);
  float successes = 0.0;  // steps taken at this level since the last descent
#if RL_WINDOWS_BY_WAY
  float layer = (s.x < 0.0 ? 1.0 : 0.0) + (s.y < 0.0 ? 2.0 : 0.0);  // the ray's window
#else
  const float layer = 0.0;
#endif
  // The loop follows the ray by depth z (= p.z + t): one add to step, one compare to test.
  const vec2 origin = p.xy - s.xy * p.z;  // where the ray's line is at depth 0
  float z = p.z;
  float step = exp2(lod) * t_texel;  // depth (and t) a step at this level covers
  for (int n = 0; n < RL_WINDOW_MAX_STEPS; n++) {
    RL_ITERATE;
    float z_next = min(z + step, 1.0);
    float bound = RL_FETCH_WINDOW(origin + s.xy * z, layer, lod);
    if (z_next < bound) {
      // Above everything the step can reach: take it, and try a longer one next.
      z = z_next;
      successes += 1.0;
      if (successes >= float(RL_CLIMB_AFTER)) {
        lod = min(lod + 1.0, rl_window_top);
        step = exp2(lod) * t_texel;
        successes = 0.0;
      }
      continue;
    }
    // Down to the bound's depth the ray is still above everything the step can reach.
    z = max(z, bound);
    if (lod > 0.0) {
      lod -= 1.0;
      step *= 0.5;
      successes = 0.0;
      continue;
    }
    float t = z - p.z, t_hit;
    if (rl_solve_cells(ray, p.z, t, min(t + float(RL_SOLVE_TEXELS) * t_texel, t_end), t_hit))
      return rl_hit_on_ray(p, s, t_hit, true);
    // Depth 1 is inside everywhere: a ray that reaches it without a root (the floor met at
    // its depth, where rounding may put the root just past the end) hits there.
    if (t_hit >= t_end) return rl_hit_on_ray(p, s, t_end, true);
    z = p.z + t_hit;
  }
  return rl_hit_on_ray(p, s, t_end, false);
}
