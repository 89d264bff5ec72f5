// Robust binary search with safety radii: Baboud & Decoret 2006, Sections 3.4-3.5.
// The ray is walked along its major axis from one centerline crossing to another: at each
// crossing the texel's safety radius r says the ray can advance r centerlines with at most
// one intersection. If it is below the surface after the step, the one crossing lies inside
// the step and a binary search finds it; if above, nothing was skipped.
// A zero radius (at domes and peaks, where rays can graze twice arbitrarily close) is
// clamped to 1 (a bounded silhouette error, the paper's Figure 7), or with
// RL_EXACT_ZERO_RADIUS the column is solved exactly (the paper's "up to two iterations of the
// exact algorithm"; here the exact bilinear walk over that column).
#include "harness/glsl/bilinear_walk.glsl"

layout(binding = 4) uniform usampler2D rl_safety_radius;  // R8UI, texels
#define RL_FETCH_RADIUS(texel) (rl_fetches++, texelFetch(rl_safety_radius, texel, 0).r)

RlHit rl_intersect(vec3 p, vec3 s) {
  const float t_end = 1.0 - p.z;
  vec2 size = vec2(textureSize(rl_relief, 0));
  ivec2 isize = ivec2(size);
  vec2 start = fract(p.xy) * size - 0.5;  // texel-centre coordinates
  vec2 dir = s.xy * size;
  int major = abs(dir.x) >= abs(dir.y) ? 0 : 1;
  // A ray entering below depth 0 (through a box proxy's side) may start inside the solid:
  // the side itself is the hit. The safety radii only bound crossings of rays from above.
  if (p.z > 0.0 && p.z >= RL_FETCH(rl_relief, p.xy).a) return rl_hit_on_ray(p, s, 0.0, true);
  if (dir[major] == 0.0) {
    // A vertical ray meets the surface straight below its entry.
    float d = RL_FETCH(rl_relief, p.xy).a;
    return rl_hit_on_ray(p, s, max(d - p.z, 0.0), true);
  }
  const float t_per_line = 1.0 / abs(dir[major]);
  // Back up to the previous centerline of the major axis (t <= 0: above the relief).
  float line0 = dir[major] > 0.0 ? floor(start[major]) : ceil(start[major]);
  float t = (line0 - start[major]) / dir[major];
  for (int n = 0; n < RL_MAX_CELLS; n++) {
    RL_ITERATE;
    // The crossing lies within texel (i, j) of the nearest centre.
    ivec2 texel = ivec2(floor(start + dir * t + 0.5));
    // Wrap into the map; not with %, undefined in GLSL for negative operands (llvmpipe wrapped
    // non-power-of-two maps wrongly that way).
    texel -= isize * ivec2(floor(vec2(texel) / vec2(isize)));
    uint r = RL_FETCH_RADIUS(texel);
#ifdef RL_EXACT_ZERO_RADIUS
    if (r == 0u) {
      float t_line = min(t + t_per_line, t_end);
      float t_hit;
      if (rl_bilinear_walk(p, s, max(t, 0.0), t_line, t_hit)) return rl_hit_on_ray(p, s, t_hit, true);
      t = t_line;
      if (t >= t_end) break;
      continue;
    }
#else
    r = max(r, 1u);
#endif
    float t_next = min(t + float(r) * t_per_line, t_end);
    float d_next = RL_FETCH(rl_relief, p.xy + s.xy * t_next).a;
    // Reaching the bottom over floor texels (depth 1) is the floor, not a crossing inside the
    // step: at most one intersection lies in the step, and a ray that entered a feature and is
    // back at depth 1 over the floor would have two. Return the floor itself so that an empty
    // floor is discarded (a binary search would return a point above it).
    if (t_next >= t_end && d_next >= 1.0) return rl_hit_on_ray(p, s, t_end, true);
    if (p.z + t_next >= d_next) {
      // Exactly one crossing in (t, t_next]: binary search, then the middle of the last interval.
      float lo = max(t, 0.0), hi = t_next;
      for (int i = 0; i < RL_BINARY_STEPS; i++) {
        RL_ITERATE;
        float mid = 0.5 * (lo + hi);
        if (p.z + mid >= RL_FETCH(rl_relief, p.xy + s.xy * mid).a) hi = mid;
        else lo = mid;
      }
      return rl_hit_on_ray(p, s, 0.5 * (lo + hi), true);
    }
    t = t_next;
    if (t >= t_end) break;
  }
  return rl_hit_on_ray(p, s, t_end, false);
}
