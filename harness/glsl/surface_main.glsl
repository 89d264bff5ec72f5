// Surface pass: per fragment of the base, trace the view ray through the relief with the
// technique's rl_intersect, shade the hit, and (only when the scene asks for self_shadow)
// trace the shadow ray of Listing 5.3, (only for scene_shadows) look the hit up in the light's
// shadow map. With RL_GBUFFER it writes the G-buffer of harness/core/gbuffer.h; without, colour
// only (the timing variant). With RL_SHADOW_CASTER it is the relief drawn into that shadow map
// from the light: the hit's depth only.
#include "harness/glsl/relief_common.glsl"
#include "harness/glsl/shading.glsl"
#ifdef RL_AMBIENT_OCCLUSION
#include "harness/glsl/ambient_occlusion.glsl"
#endif
#ifdef RL_SCENE_SHADOWS
#include "harness/glsl/shadow_map.glsl"
#endif

in vec3 v_world;
in vec2 v_uv;
in vec3 v_dpdu;
in vec3 v_dpdv;
in vec3 v_normal;
in float v_entry_depth;
in vec2 v_curvature;

uniform vec3 rl_eye;
uniform vec3 rl_light;
uniform float rl_depth_scale;  // world depth of depth 1
#ifdef RL_DEPTH_CORRECT
uniform mat4 rl_view_projection;
#endif
#ifdef RL_PROXY_BOX
uniform vec2 rl_uv_max;  // the box spans [0, rl_uv_max] in u and v
#endif
#ifdef RL_REVERSE_PERSPECTIVE
// Reverse-perspective texture space (Baboud & Decoret, Section 4; scene.h ReverseProjection):
// the base's affine coordinates a map projectively to texture space, centre of projection at
// depth rl_cop under the box's centre. The vertices carry affine coordinates.
uniform float rl_cop;
uniform vec3 rl_eye_affine;
vec3 rl_project(vec3 a) {
  float k = rl_cop / (rl_cop - a.z);
  return vec3(0.5 + (a.xy - 0.5) * k, a.z * (rl_cop - 1.0) / (rl_cop - a.z));
}
vec3 rl_unproject(vec3 t) {
  float z = t.z * rl_cop / (rl_cop - 1.0 + t.z);
  return vec3(0.5 + (t.xy - 0.5) * ((rl_cop - z) / rl_cop), z);
}
#endif
#ifdef RL_SELF_SHADOW
uniform float rl_shadow_bias;  // depth units (Listing 5.3's shadow_threshold)
#endif

#include "harness/glsl/gbuffer_outputs.glsl"

// A world direction in texture units per world unit: (du, dv, d depth). The floor keeps a
// collapsed mapping (a sphere's pole) finite.
vec3 rl_texture_direction(vec3 d, vec3 n) {
  return vec3(dot(d, v_dpdu) / max(dot(v_dpdu, v_dpdu), 1e-30),
              dot(d, v_dpdv) / max(dot(v_dpdv, v_dpdv), 1e-30), -dot(d, n) / rl_depth_scale);
}

void main() {
#if defined(RL_SHADOW_CASTER) && !defined(RL_DEPTH_CORRECT)
  // Drawn into the shadow map at its base's depth: there is nothing to search.
  o_color = vec4(0.0);
  rl_count_fragment();
  return;
#endif
#ifdef RL_MIPMAP
  // The footprint of this pixel on the texture, while control flow is still uniform.
  rl_uv_dx = dFdx(v_uv);
  rl_uv_dy = dFdy(v_uv);
#endif
  rl_depth_aspect = rl_depth_scale / max(vec2(length(v_dpdu), length(v_dpdv)), vec2(1e-30));
  vec3 N = normalize(v_normal);
  vec3 V = normalize(v_world - rl_eye);
  vec3 tv = rl_texture_direction(V, N);
  bool t_is_world = false;  // h.t counts world units along V (bent-ray searches)
#ifdef RL_IMPOSTOR
  // Relief impostors (Policarpo & Oliveira 2006, Section 4): the quad runs through the
  // object's middle (depth 0.5) and is seen from either side; the search covers the whole
  // depth range along the ray, downward from the front, upward from behind, and a ray that
  // meets no layer shows what lies behind the impostor.
  if (tv.z == 0.0) RL_DISCARD;
  vec3 s = tv / abs(tv.z);
  RlHit h = rl_intersect(vec3(v_uv, 0.5) - 0.5 * s, s);
  if (!h.hit) RL_DISCARD;
#elif defined(RL_TWO_SIDED)
  // A pattern with gaps on a closed base (Policarpo & Oliveira 2006, Figure 1 and Section 5):
  // through a gap the far side shows, its relief seen from inside. A back face's ray crossed
  // the relief from depth 1 up to the base (depth 0) before reaching the fragment, so it is
  // searched upward from there.
  if (tv.z == 0.0) RL_DISCARD;
  vec3 s = tv / abs(tv.z);
#ifdef RL_SILHOUETTE
  // Front faces bend their ray through the fragment's quadric (chapter 5 silhouettes, as
  // below); the far side, seen from inside through a gap, is searched planar.
  RlHit h;
  if (tv.z > 0.0) {
    vec3 metric = vec3(length(v_dpdu), length(v_dpdv), rl_depth_scale);
    h = rl_intersect_curved(vec3(v_uv, 0.0), tv, v_curvature, metric);
    t_is_world = true;
  } else {
    h = rl_intersect(vec3(v_uv, 0.0) - s, s);
  }
#else
  RlHit h = rl_intersect(tv.z > 0.0 ? vec3(v_uv, 0.0) : vec3(v_uv, 0.0) - s, s);
#endif
  if (!h.hit) RL_DISCARD;
#else
  if (tv.z <= 0.0) RL_DISCARD;  // base seen from below: no relief there
#endif
#if defined(RL_IMPOSTOR) || defined(RL_TWO_SIDED)
#elif defined(RL_REVERSE_PERSPECTIVE)
  // Lines stay lines: the ray through the projected eye and the projected fragment.
  vec3 a_frag = vec3(v_uv, v_entry_depth);
  vec3 p_tex = rl_project(a_frag);
  vec3 e_tex = rl_project(rl_eye_affine);
  vec3 s = (p_tex - e_tex) / (p_tex.z - e_tex.z);
  RlHit h = rl_intersect(p_tex, s);
#elif defined(RL_SILHOUETTE)
  // Chapter 5, "Silhouette edges": the base bends away from the fragment's tangent plane as
  // the quadric of its interpolated curvature; the technique searches the bent ray (t in world
  // units along V) and reports a miss where the ray leaves the relief: outside the silhouette.
  vec3 metric = vec3(length(v_dpdu), length(v_dpdv), rl_depth_scale);
  RlHit h = rl_intersect_curved(vec3(v_uv, 0.0), tv, v_curvature, metric);
  t_is_world = true;
#if defined(RL_LAYERED_FLOOR) && !defined(RL_EMPTY_FLOOR)
  // A pattern over its solid floor (the underlying model): a ray that reached depth 1 through
  // the gaps ends on it; one that left through the top is outside the silhouette.
  if (!h.hit && h.depth < 1.0 - 1e-4) RL_DISCARD;
#else
  if (!h.hit) RL_DISCARD;
#endif
#else
  vec3 s = tv / tv.z;
  RlHit h = rl_intersect(vec3(v_uv, v_entry_depth), s);
#endif
#ifdef RL_PROXY_BOX
  // A hit outside the box means the ray left it first (the box is convex, rays straight).
  const float eps = 1e-5;
  if (any(lessThan(h.uv, vec2(-eps))) || any(greaterThan(h.uv, rl_uv_max + eps))) RL_DISCARD;
  // Reaching depth 1 is the floor: a hit on a solid floor (a search may end there without
  // a root, by rounding), or leaving the box through an empty one.
  bool on_floor = h.depth >= 1.0 - 1e-4;
#ifdef RL_EMPTY_FLOOR
  if (on_floor) RL_DISCARD;
#endif
  if (!h.hit && !on_floor) RL_DISCARD;  // a walk stopped by its cell cap
#elif defined(RL_EMPTY_FLOOR) && !defined(RL_IMPOSTOR) && !defined(RL_TWO_SIDED)
  // The base drawn over an empty floor (a non-height-field pattern): a ray that finds no
  // surface, or only the floor, went through the pattern's gaps.
  if (!h.hit || h.depth >= 1.0 - 1e-4) RL_DISCARD;
#endif

  // The point the technique claims: its hit uv at its hit depth, in the base's frame.
#ifdef RL_REVERSE_PERSPECTIVE
  vec3 a_hit = rl_unproject(vec3(h.uv, h.depth));
#else
  vec3 a_hit = vec3(h.uv, h.depth);
#endif
  // A bent-ray search gives the world distance along the straight view ray; the others a point
  // in the base's frame.
  vec3 hit_world = t_is_world ? v_world + V * h.t
                              : v_world + v_dpdu * (a_hit.x - v_uv.x) +
                                    v_dpdv * (a_hit.y - v_uv.y) -
                                    N * ((a_hit.z - v_entry_depth) * rl_depth_scale);
#ifdef RL_DEPTH_CORRECT
  // Chapter 5, "Depth Correct": the depth of the found hit, so that other geometry (and other
  // relief objects) resolve visibility per pixel against the relief, not against its base.
  vec4 hit_clip = rl_view_projection * vec4(hit_world, 1.0);
  gl_FragDepth = clamp(0.5 * hit_clip.z / hit_clip.w + 0.5, 0.0, 1.0);
#endif
#ifdef RL_SHADOW_CASTER
  o_color = vec4(0.0);
  rl_count_fragment();
  return;
#endif
#ifdef RL_HIT_ATTRIBUTES
  // The technique's own normal and colour of the hit (e.g. a multilayer map's layer).
  vec3 tn, albedo;
  rl_hit_attributes(h, tn, albedo);
#else
  vec3 tn = rl_decode_normal(rl_relief_texel(h.uv));
  vec3 albedo = RL_FETCH_COLOR(h.uv).rgb;
#endif
  vec3 n = normalize(tn.x * normalize(v_dpdu) + tn.y * normalize(v_dpdv) + tn.z * N);
  vec3 to_light = normalize(rl_light - hit_world);

  bool in_shadow = false;
#ifdef RL_SELF_SHADOW
  // Listing 5.3: enter the relief where the light ray crosses the top, search along it, and
  // call the pixel shadowed when that search stops clearly above our hit.
  vec3 tl = rl_texture_direction(-to_light, N);
#ifdef RL_IMPOSTOR
  // An impostor is lit from either side: the light ray enters the depth range at 0 (light
  // above) or at 1 (below) and is searched toward the hit.
  if (tl.z != 0.0) {
    vec3 sl = tl / abs(tl.z);
    float travel = tl.z > 0.0 ? h.depth : 1.0 - h.depth;
    RlHit hl = rl_intersect(vec3(h.uv, h.depth) - sl * travel, sl);
    in_shadow = hl.hit && (tl.z > 0.0 ? hl.depth < h.depth - rl_shadow_bias
                                      : hl.depth > h.depth + rl_shadow_bias);
  }
#else
  if (tl.z <= 0.0) {
    in_shadow = true;  // light at or below the hit
  } else {
    vec3 sl = tl / tl.z;
    RlHit hl = rl_intersect(vec3(h.uv - sl.xy * h.depth, 0.0), sl);
    in_shadow = hl.hit && hl.depth < h.depth - rl_shadow_bias;
  }
#endif
#endif
#ifdef RL_SCENE_SHADOWS
  // Policarpo & Oliveira 2006, Section 7: what the light's shadow map holds -- the objects, and
  // the relief at its found hits' depths -- shadows the hit as it does any surface.
#ifdef RL_SHADOW_AT_BASE
  // What a shadow map of the undisplaced surface gives: looked up where the base is drawn.
  in_shadow = in_shadow || rl_in_scene_shadow(v_world, N);
#else
  in_shadow = in_shadow || rl_in_scene_shadow(hit_world, n);
#endif
#endif

#ifdef RL_AMBIENT_OCCLUSION
  rl_ambient_visibility = rl_ambient_occlusion(h.uv);
#endif
  o_color = vec4(rl_shade(albedo, n, to_light, -V, in_shadow), 1.0);
#ifdef RL_GBUFFER
  o_position = vec4(hit_world, 1.0);
  o_normal = vec4(n, in_shadow ? 1.0 : 0.0);
  o_hit = vec4(h.uv, float(h.layer), float(rl_fetches));
  o_aux = vec4(rl_ambient_visibility, 0.0, dot(rl_ambient * albedo, vec3(1.0 / 3.0)), 0.0);
#endif
  rl_count_fragment();
}
