// Shared by every single-layer technique: texture bindings, the fetch counter, the hit record.

// rgb: tangent-space normal * 0.5 + 0.5 (z out of the surface); a: depth, 0 top, 1 bottom.
layout(binding = 0) uniform sampler2D rl_relief;
layout(binding = 1) uniform sampler2D rl_color;

// World relief depth / world length of one unit of u (x) and of v (y) at this fragment:
// converts a texture-space step back to a unit tangent-space direction (parallax's offset
// limiting needs its z). Per axis, since a non-square map's texture units differ in world
// length. Set by the pass's main() before the search: per fragment on curved bases, from
// rl_probe_depth_aspect in ray-probe mode.
vec2 rl_depth_aspect = vec2(1.0);

// Every texture read of a technique goes through RL_FETCH, so fetch counts compare across
// techniques. Level 0 explicitly: searches run in non-uniform control flow, where implicit
// derivatives are undefined, and the truth reconstructs the level-0 bilinear surface.
int rl_fetches = 0;

#ifdef RL_PROBE
// Probe rays may carry a base quadric (A, B) for techniques that bend rays (chapter 5
// silhouettes); zero for the planar tangent space.
vec2 rl_probe_quadric = vec2(0.0);
#endif
#define RL_FETCH(tex, uv) (rl_fetches++, textureLod(tex, uv, 0.0))

// A found hit. The ray is (u, v, depth)(t) = p + t * s with s.z = 1, so depth = p.z + t.
struct RlHit {
  vec2 uv;      // texture coordinate of the hit
  float depth;  // depth of the hit, 0 (top) to 1 (bottom)
  float t;      // ray parameter (depth units travelled)
  int layer;    // layer of a multilayer map (0 for heightfields)
  bool hit;     // false: the routine found no surface
};

// normalize(rgb * 2 - 1); a texel that encodes the zero vector (quantised mid-grey) gives the
// base normal instead of NaN. relief_map.cpp's decode_normal() is the same on the CPU.
vec3 rl_decode_normal(vec4 texel) {
  vec3 n = texel.xyz * 2.0 - 1.0;
  float len = length(n);
  return len > 0.0 ? n / len : vec3(0.0, 0.0, 1.0);
}

// Normal and colour where a search ends without a surface and the pass still draws it (on a
// floor): a multilayer map's solid floor faces up in its floor colour (RL_LAYERED_FLOOR, set by
// layered_floor_define()); a heightfield's floor texel has its own normal and colour.
void rl_floor_attributes(vec2 uv, out vec3 tn, out vec3 albedo) {
#ifdef RL_LAYERED_FLOOR
  tn = vec3(0.0, 0.0, 1.0);
  albedo = RL_LAYERED_FLOOR;
#else
  tn = rl_decode_normal(RL_FETCH(rl_relief, uv));
  albedo = RL_FETCH(rl_color, uv).rgb;
#endif
}

RlHit rl_hit_on_ray(vec3 p, vec3 s, float t, bool hit) {
  RlHit h;
  h.t = t;
  h.uv = p.xy + s.xy * t;
  h.depth = p.z + t;
  h.layer = 0;
  h.hit = hit;
  return h;
}
