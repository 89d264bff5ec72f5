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

// rl_fetches, rl_iterations
#include "harness/glsl/search_cost.glsl"

#ifdef RL_PROBE
// Probe rays may carry a base quadric (A, B) for techniques that bend rays (chapter 5
// silhouettes); zero for the planar tangent space.
vec2 rl_probe_quadric = vec2(0.0);
#endif
// Every texture read of a technique goes through RL_FETCH, so fetch counts compare across
// techniques. Level 0 explicitly: searches run in non-uniform control flow, where implicit
// derivatives are undefined, and the truth reconstructs the level-0 bilinear surface.
#define RL_FETCH(tex, uv) (rl_fetches++, textureLod(tex, uv, 0.0))

// normalize(rgb * 2 - 1); a texel that encodes the zero vector (quantised mid-grey) gives the
// base normal instead of NaN. relief_map.cpp's decode_normal() is the same on the CPU.
vec3 rl_decode_normal(vec4 texel) {
  vec3 n = texel.xyz * 2.0 - 1.0;
  float len = length(n);
  return len > 0.0 ? n / len : vec3(0.0, 0.0, 1.0);
}

#ifdef RL_MIPMAP
// Mip-mapped reads (chapter 5, "Texture filtering and mip-mapping"; Policarpo & Oliveira,
// Section 6): the footprint of the fragment's pixel on the texture, the gradients of the
// base's texture coordinate across it, which the pass's main() sets before the search while
// control flow is uniform; zero (level 0) for probe rays, which have no footprint.
vec2 rl_uv_dx = vec2(0.0), rl_uv_dy = vec2(0.0);
#define RL_FETCH_GRAD(tex, uv) (rl_fetches++, textureGrad(tex, uv, rl_uv_dx, rl_uv_dy))
#endif

#ifdef RL_COLOR_MIPMAP
// The colour from its own mip chain at the pixel's footprint (Baboud & Decoret 2006, Section 6:
// "mipmapping for the color texture can be a solution" to geometric aliasing); the geometry
// stays at level 0. Needs RL_MIPMAP's footprint.
layout(binding = 19) uniform sampler2D rl_color_mipmapped;
#define RL_FETCH_COLOR(uv) RL_FETCH_GRAD(rl_color_mipmapped, uv)
#else
#define RL_FETCH_COLOR(uv) RL_FETCH(rl_color, uv)
#endif

#ifdef RL_META_LAYERS
// A meta-relief combined per fetch (Limberger, Schetinger & Oliveira, Eqs. 1-2; the CPU's
// relief/meta_relief.cpp evaluates the same): layer i is sampled at its own tiling and
// resolution, normals and depths weighted by w / sum w. Every layer's read is a counted fetch.
layout(binding = 10) uniform sampler2D rl_meta_layer[RL_META_LAYERS];
uniform float rl_meta_tiling[RL_META_LAYERS];
uniform float rl_meta_normal_share[RL_META_LAYERS];  // w_n / sum w_n
uniform float rl_meta_depth_share[RL_META_LAYERS];   // w_d / sum w_d

vec4 rl_relief_texel(vec2 uv) {
  vec3 n = vec3(0.0);
  float d = 0.0;
  for (int i = 0; i < RL_META_LAYERS; ++i) {
    vec4 texel = RL_FETCH(rl_meta_layer[i], uv * rl_meta_tiling[i]);
    n += rl_meta_normal_share[i] * rl_decode_normal(texel);
    d += rl_meta_depth_share[i] * texel.a;
  }
  float len = length(n);
  return vec4((len > 0.0 ? n / len : vec3(0.0, 0.0, 1.0)) * 0.5 + 0.5, d);
}

float rl_relief_depth(vec2 uv) {
  float d = 0.0;
  for (int i = 0; i < RL_META_LAYERS; ++i)
    d += rl_meta_depth_share[i] * RL_FETCH(rl_meta_layer[i], uv * rl_meta_tiling[i]).a;
  return d;
}
#elif defined(RL_MIPMAPPED_RELIEF)
// Normals and depths from the relief's mip chain (gpu/mipmapped_relief.h), trilinear at
// the pixel's footprint. The colour stays at level 0, as the truth shades it, so the error
// columns see what mip-mapping does to the geometry alone.
layout(binding = 9) uniform sampler2D rl_relief_mipmapped;
vec4 rl_relief_texel(vec2 uv) { return RL_FETCH_GRAD(rl_relief_mipmapped, uv); }
float rl_relief_depth(vec2 uv) { return rl_relief_texel(uv).a; }
#elif defined(RL_AO_PACKED)
// The AO map in the relief texture's blue channel (Limberger et al., Section IV;
// gpu/packed_relief.h): R and G the normal's x and y, its z rebuilt; alpha the depth.
// A texel's read keeps its AO for the shading (ambient_occlusion.glsl), which reads the hit's
// normal first: the AO costs no fetch of its own.
layout(binding = 20) uniform sampler2D rl_relief_packed;
float rl_packed_ao = 1.0;
vec4 rl_relief_texel(vec2 uv) {
  vec4 t = RL_FETCH(rl_relief_packed, uv);
  rl_packed_ao = t.b;
  vec2 xy = t.xy * 2.0 - 1.0;
  return vec4(vec3(xy, sqrt(max(0.0, 1.0 - dot(xy, xy)))) * 0.5 + 0.5, t.a);
}
float rl_relief_depth(vec2 uv) { return RL_FETCH(rl_relief_packed, uv).a; }
#else
// The relief texel (normal rgb, depth a) and depth at uv: one fetch of the map.
vec4 rl_relief_texel(vec2 uv) { return RL_FETCH(rl_relief, uv); }
float rl_relief_depth(vec2 uv) { return RL_FETCH(rl_relief, uv).a; }
#endif


// A found hit. The ray is (u, v, depth)(t) = p + t * s with s.z = 1, so depth = p.z + t.
struct RlHit {
  vec2 uv;      // texture coordinate of the hit
  float depth;  // depth of the hit, 0 (top) to 1 (bottom)
  float t;      // ray parameter (depth units travelled)
  int layer;    // layer of a multilayer map (0 for heightfields)
  bool hit;     // false: the routine found no surface
};

// Normal and colour where a search ends without a surface and the pass still draws it (on a
// floor): a multilayer map's solid floor faces up in its floor colour (RL_LAYERED_FLOOR, set by
// layered_floor_define()); a heightfield's floor texel has its own normal and colour.
void rl_floor_attributes(vec2 uv, out vec3 tn, out vec3 albedo) {
#ifdef RL_LAYERED_FLOOR
  tn = vec3(0.0, 0.0, 1.0);
  albedo = RL_LAYERED_FLOOR;
#else
  tn = rl_decode_normal(rl_relief_texel(uv));
  albedo = RL_FETCH_COLOR(uv).rgb;
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
