// Relief texture mapping by multi-pass depth slicing (chapter 5, "RTM - Multi pass for planar
// objects", Listing 5.2): each pass rasterises one slice plane through the relief's volume; a
// fragment is kept where the plane lies behind the stored surface (Pass 1/2/3 of the chapter:
// "depth is greater than RTM object depth ... render", else discard) and the depth test keeps
// the nearest kept slice per pixel. So a surface at depth D shows at the first slice behind it
// along the view ray: the error is a function of the number of slices.
//
// RL_FACES: an object from several heightfields (heightfield_faces.glsl), a fragment kept when
// inside every face's solid (Listing 5.2's front/back "inside range" test, for any faces).
// Otherwise the scene's single map on units 0 (relief) and 1 (colour), repeating.
// RL_COUNT_FRAGMENTS: every fragment adds itself and its fetches to two r32ui images, so the
// cost per pixel counts all slices' fragments, not only the one kept.
// Outside the #ifdef: the shader library inlines each file once, wherever it is first included.
#include "harness/glsl/search_cost.glsl"
#ifdef RL_FACES
#include "harness/glsl/heightfield_faces.glsl"
#else
layout(binding = 0) uniform sampler2D rl_relief;
layout(binding = 1) uniform sampler2D rl_color;
// As in heightfield_faces.glsl: an empty column (a mesh's bake missed). RL_SLICE_SLACK (from
// the plugin): on an 8-bit map, the slack that puts a slice exactly at a stored depth inside
// whatever the rounding.
const float RL_EMPTY_DEPTH = 1.0 - 0.5 / 255.0;
#endif
#include "harness/glsl/shading.glsl"

#ifdef RL_PROBE
#include "harness/glsl/probe_io.glsl"
// The slices' depths in the map's (or each face's) texture space, nearest the face first.
uniform float rl_slice_depth[RL_SLICES];
#endif

#ifdef RL_COUNT_FRAGMENTS
layout(binding = 0, r32ui) uniform coherent uimage2D rl_fragment_count;
layout(binding = 1, r32ui) uniform coherent uimage2D rl_fetch_count;
#endif

#ifndef RL_PROBE
in vec3 v_tex;
#endif

uniform vec3 rl_eye;
uniform vec3 rl_light;
uniform mat4 rl_world_from_texture;
uniform mat3 rl_normal_from_texture;

#ifndef RL_PROBE
#include "harness/glsl/gbuffer_outputs.glsl"
#endif

// Is the slice point p (texture space) behind the surface? Then its world normal (not yet
// normalised) and albedo.
bool rl_slice_keeps(vec3 p, out vec3 normal, out vec3 albedo, out float layer) {
  normal = vec3(0.0, 0.0, 1.0);
  albedo = vec3(0.0);
  layer = 0.0;
#ifdef RL_FACES
  int surface;
  if (!rl_faces_inside(p, surface)) return false;
  vec3 tn;
  rl_face_attributes(surface, p, tn, albedo);
  normal = rl_normal_from_texture * tn;
  layer = float(surface);
  return true;
#else
  ++rl_fetches;
  vec4 r = texture(rl_relief, p.xy);
#ifdef RL_EMPTY_FLOOR
  if (r.a >= RL_EMPTY_DEPTH) return false;
#endif
  if (p.z < r.a - RL_SLICE_SLACK) return false;
  ++rl_fetches;
  albedo = texture(rl_color, p.xy).rgb;
  // The map's normal is already the world's on the planar base (its slopes at the world's
  // texel size and depth).
  normal = r.rgb * 2.0 - 1.0;
  return true;
#endif
}

#ifdef RL_PROBE
// The slices along one ray, as the rasteriser would meet them: the nearest slice point (smallest
// t) that is kept. Face-aligned slices are planes of constant (face) texture depth; view-aligned
// ones are planes across the ray, so along it they are RL_SLICES evenly spaced points over its
// chord through the volume (a linear search without refinement).
void main() {
  vec4 origin, direction;
  rl_probe_ray(origin, direction);
  vec3 o = origin.xyz, d = direction.xyz;
  float best = 1e30;
  float best_layer = 0.0;
  vec3 nw, albedo;
  float layer;
#ifdef RL_FACES
  // Cube texture space, any direction, from inside the cube to its exit.
  vec3 safe = mix(d, vec3(1e-9), lessThan(abs(d), vec3(1e-9)));
  vec3 far = max((vec3(0.0) - o) / safe, (vec3(1.0) - o) / safe);
  float t_end = max(0.0, min(min(far.x, far.y), far.z));
#ifdef RL_VIEW_ALIGNED
  for (int s = 0; s < RL_SLICES && best > 1e29; ++s) {
    RL_ITERATE;
    float t = t_end * (float(s) + 0.5) / float(RL_SLICES);
    if (rl_slice_keeps(o + d * t, nw, albedo, layer)) best = t, best_layer = layer;
  }
#else
  for (int k = 0; k < rl_face_count; ++k) {
    vec3 a0 = rl_face_from_cube[k] * (o - 0.5) + 0.5;
    float dz = (rl_face_from_cube[k] * d).z;
    for (int s = 0; s < RL_SLICES; ++s) {
      RL_ITERATE;
      // The slice's affine depth (ReverseProjection::affine_from_texture).
      float z = rl_slice_depth[s];
      if (rl_face_cop > 1.0) z = z * rl_face_cop / (rl_face_cop - 1.0 + z);
      if (abs(dz) < 1e-9) continue;  // along the slice planes: they are met edge-on
      float t = (z - a0.z) / dz;
      if (t < 0.0 || t > t_end || t >= best) continue;
      if (rl_slice_keeps(o + d * t, nw, albedo, layer)) best = t, best_layer = layer;
    }
  }
#endif
#else
  // Tangent space, direction.z = 1 (t counts depth units), down to the floor.
#ifdef RL_VIEW_ALIGNED
  for (int s = 0; s < RL_SLICES && best > 1e29; ++s) {
    RL_ITERATE;
    float t = (1.0 - o.z) * (float(s) + 1.0) / float(RL_SLICES);
    if (rl_slice_keeps(o + d * t, nw, albedo, layer)) best = t;
  }
#else
  for (int s = 0; s < RL_SLICES && best > 1e29; ++s) {
    RL_ITERATE;
    float t = rl_slice_depth[s] - o.z;
    if (t < 0.0) continue;
    if (rl_slice_keeps(o + d * t, nw, albedo, layer)) best = t;
  }
#endif
#endif
  bool hit = best < 1e29;
  vec3 p = o + d * (hit ? best : 0.0);
  rl_probe_write(hit ? best : 0.0, p.xy, p.z, best_layer, hit, rl_fetches);
}
#else
void main() {
  vec3 nw, albedo;
  float layer;
  bool keep = rl_slice_keeps(v_tex, nw, albedo, layer);
#ifdef RL_COUNT_FRAGMENTS
  ivec2 px = ivec2(gl_FragCoord.xy);
  imageAtomicAdd(rl_fragment_count, px, 1u);
  imageAtomicAdd(rl_fetch_count, px, uint(rl_fetches));
#endif
  rl_count_fragment();  // every slice fragment, kept or not
  if (!keep) discard;
  vec3 world = (rl_world_from_texture * vec4(v_tex, 1.0)).xyz;
  vec3 V = normalize(world - rl_eye);
  nw = dot(nw, nw) > 0.0 ? normalize(nw) : -V;
#ifdef RL_FACES
  if (dot(nw, V) > 0.0) nw = -nw;  // facing the viewer, as the truth's mesh normals
#endif
  vec3 to_light = normalize(rl_light - world);
  o_color = vec4(rl_shade(albedo, nw, to_light, -V, false), 1.0);
#ifdef RL_GBUFFER
  o_position = vec4(world, 1.0);
  o_normal = vec4(nw, 0.0);
  o_hit = vec4(v_tex.xy, layer, float(rl_fetches));  // fetches: replaced by the resolve pass
  o_aux = vec4(1.0, 0.0, dot(rl_ambient * albedo, vec3(1.0 / 3.0)), 0.0);
#endif
}
#endif
