// Relief mapping with double depth values: book chapter 5, 'Single RTM with Double Depth
// values (restricted 3D objects)', after Angel & Christ. One RGBA texel holds the front
// surface's normal x and y, the front depth (looking from the top) and the back depth
// (looking from the bottom); a point is inside the object when its depth lies between the two.
// The search is Listing 5.3's with that extra comparison in the linear and the binary steps;
// a ray that never gets inside misses (the chapter's capping: alpha = 0 where d = 1).
#include "harness/glsl/relief_common.glsl"

#define RL_HIT_ATTRIBUTES 1

layout(binding = 4) uniform sampler2D rl_double_depth;  // (nx * 0.5 + 0.5, ny * 0.5 + 0.5, front, back)

bool rl_inside_double(vec2 uv, float d) {
  vec4 t = RL_FETCH(rl_double_depth, uv);
  return d >= t.z && d <= t.w;
}

RlHit rl_intersect(vec3 p, vec3 s) {
  float size = (1.0 - p.z) / float(RL_LINEAR_STEPS);
  float t = 0.0;
  bool found = false;
  for (int i = 1; i <= RL_LINEAR_STEPS; i++) {
    RL_ITERATE;
    t = size * float(i);
    if (rl_inside_double(p.xy + s.xy * t, p.z + t)) {
      found = true;
      break;
    }
  }
  if (!found) {
    RlHit miss = rl_hit_on_ray(p, s, 1.0 - p.z, false);
    miss.layer = -1;
    return miss;
  }
  float lo = t - size, hi = t;
  for (int i = 0; i < RL_BINARY_STEPS; i++) {
    RL_ITERATE;
    float mid = 0.5 * (lo + hi);
    if (rl_inside_double(p.xy + s.xy * mid, p.z + mid))
      hi = mid;
    else
      lo = mid;
  }
  return rl_hit_on_ray(p, s, hi, true);
}

// The front surface's normal (x, y stored, z rebuilt) and the map's colour; a miss drawn on
// the floor shades as multilayer's does.
void rl_hit_attributes(RlHit h, out vec3 tn, out vec3 albedo) {
  if (h.layer < 0) {
    rl_floor_attributes(h.uv, tn, albedo);
    return;
  }
  albedo = RL_FETCH(rl_color, h.uv).rgb;
  vec2 xy = RL_FETCH(rl_double_depth, h.uv).xy * 2.0 - 1.0;
  tn = vec3(xy, sqrt(max(0.0, 1.0 - dot(xy, xy))));
}
