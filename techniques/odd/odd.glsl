// Omni-directional displacement maps (chapter 5, Listing 5.9): no search. The view direction's
// angles (a, b) pick one of the stored directions, the fragment's texture coordinate a super
// pixel, and the 4D texel there gives the normal and the depth of the first hit along that
// stored ray; the hit is placed on the view ray at that depth, where the colour is read (the
// listing's "diffuse texture mapping using depth as offset").
//
// rl_odd holds the 4D map in one 2D texture (odd_map.h): direction-major (a, b, x, y), A x B
// tiles of X x Y, or spatial-major (x, y, a, b), X x Y tiles of A x B. The listing floors the
// outer pair and lets the hardware filter the inner one: direction-major interpolates space
// between super pixels, spatial-major interpolates directions. RL_ODD_INTERPOLATE blends the
// floored pair too, bilinearly over its four nearest cells (four fetches).
layout(binding = 1) uniform sampler2D rl_color;
layout(binding = 4) uniform sampler2D rl_odd;

uniform int rl_odd_spatial;     // X = Y: super pixels per tile side
uniform int rl_odd_directions;  // A = B: directions per angle

#include "harness/glsl/search_cost.glsl"
const float RL_PI = 3.14159265358979;

// (a, b) / pi of a direction (z into the surface) by the chapter's formulas, the cosines
// clamped to [-1, 1]: rounding pushes them past it at a = 0 or pi, and acos is NaN there.
vec2 rl_odd_angles(vec3 v) {
  float B = clamp(v.y, -1.0, 1.0);
  float s = sqrt(max(0.0, 1.0 - B * B));
  float A = s > 1e-6 ? clamp(v.x / s, -1.0, 1.0) : 0.0;
  return vec2(acos(A), acos(B)) / RL_PI;
}

vec4 rl_odd_texel(vec2 outer_cell, vec2 inner, float outer_count, float inner_count) {
  ++rl_fetches;
  vec2 coord = outer_cell * inner_count + clamp(inner, vec2(0.5), vec2(inner_count - 0.5));
  return textureLod(rl_odd, coord / (outer_count * inner_count), 0.0);
}

// The 4D texel at spatial coordinate `sp` (super pixels, [0, X) within the tile) and direction
// coordinate `dc` ((a, b) / pi * A, in [0, A)).
vec4 rl_odd_lookup(vec2 sp, vec2 dc) {
  float X = float(rl_odd_spatial), N = float(rl_odd_directions);
#ifdef RL_ODD_DIRECTION_MAJOR
  vec2 outer = dc;
  vec2 inner = sp;
  float outer_count = N, inner_count = X;
#else
  vec2 outer = sp;
  vec2 inner = dc;
  float outer_count = X, inner_count = N;
#endif
#ifdef RL_ODD_INTERPOLATE
  vec2 f = outer - 0.5;
  vec2 c0 = floor(f);
  vec2 w = f - c0;
  vec4 sum = vec4(0.0);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      vec2 c = c0 + vec2(i, j);
#ifdef RL_ODD_DIRECTION_MAJOR
      c = clamp(c, vec2(0.0), vec2(outer_count - 1.0));  // directions end at 0 and pi
#else
      c = c - outer_count * floor(c / outer_count);  // the surface tiles: space wraps
#endif
      float weight = (i == 1 ? w.x : 1.0 - w.x) * (j == 1 ? w.y : 1.0 - w.y);
      sum += weight * rl_odd_texel(c, inner, outer_count, inner_count);
    }
  return sum;
#else
  vec2 c = clamp(floor(outer), vec2(0.0), vec2(outer_count - 1.0));
  return rl_odd_texel(c, inner, outer_count, inner_count);
#endif
}

// Spatial coordinate of a texture coordinate (the tile repeats).
vec2 rl_odd_spatial_coord(vec2 uv) { return fract(uv) * float(rl_odd_spatial); }

#ifdef RL_PROBE
#include "harness/glsl/probe_io.glsl"
uniform vec2 rl_depth_aspect;  // world depth / world length of u, of v

void main() {
  vec4 origin, direction;
  rl_probe_ray(origin, direction);
  vec3 o = origin.xyz, d = direction.xyz;  // d.z = 1: t counts depth units
  vec3 v = normalize(vec3(d.x / rl_depth_aspect.x, d.y / rl_depth_aspect.y, 1.0));
  vec4 texel =
      rl_odd_lookup(rl_odd_spatial_coord(o.xy), rl_odd_angles(v) * float(rl_odd_directions));
  float t = max(texel.a - o.z, 0.0);
  vec3 p = o + d * t;
  rl_probe_write(t, p.xy, p.z, 0.0, true, rl_fetches);
}
#else
#include "harness/glsl/shading.glsl"

in vec3 v_world;
in vec2 v_uv;
in vec3 v_dpdu;
in vec3 v_dpdv;
in vec3 v_normal;

uniform vec3 rl_eye;
uniform vec3 rl_light;
uniform mat4 rl_view_projection;
uniform float rl_depth_scale;  // world depth of the relief

#include "harness/glsl/gbuffer_outputs.glsl"

void main() {
  vec3 T = normalize(v_dpdu), B = normalize(v_dpdv), N = normalize(v_normal);
  vec3 V = normalize(v_world - rl_eye);
  float down = -dot(V, N);  // > 0 for a fragment of the base seen from above
  if (down <= 0.0) RL_DISCARD;
  vec3 v = vec3(dot(V, T), dot(V, B), down);
  vec4 texel = rl_odd_lookup(rl_odd_spatial_coord(v_uv), rl_odd_angles(v) *
                                                             float(rl_odd_directions));
  // The hit on the view ray at the stored depth.
  float t = texel.a * rl_depth_scale / down;
  vec3 hit_world = v_world + V * t;
  vec2 hit_uv = v_uv + vec2(v.x / length(v_dpdu), v.y / length(v_dpdv)) * t;
  vec4 hit_clip = rl_view_projection * vec4(hit_world, 1.0);
  gl_FragDepth = clamp(0.5 * hit_clip.z / hit_clip.w + 0.5, 0.0, 1.0);
  vec3 tn = texel.rgb * 2.0 - 1.0;
  vec3 nw = normalize(T * tn.x + B * tn.y + N * tn.z);
  ++rl_fetches;
  vec3 albedo = texture(rl_color, hit_uv).rgb;
  vec3 to_light = normalize(rl_light - hit_world);
  o_color = vec4(rl_shade(albedo, nw, to_light, -V, false), 1.0);
#ifdef RL_GBUFFER
  o_position = vec4(hit_world, 1.0);
  o_normal = vec4(nw, 0.0);
  o_hit = vec4(hit_uv, 0.0, float(rl_fetches));
  o_aux = vec4(1.0, 0.0, dot(rl_ambient * albedo, vec3(1.0 / 3.0)), 0.0);
#endif
  rl_count_fragment();
}
#endif
