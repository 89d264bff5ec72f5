// Ray casting of a cell complex (Apaza & Andujar, Section 3.5.2): per fragment of a proxy face,
// the view ray in grid coordinates is searched linearly and refined by bisection
// (cell_complex_common.glsl); the hit's normal and colour come from its face's maps. The hit's
// depth is always written: the proxy's fragments along one pixel resolve by it. With RL_PROBE,
// a ray-probe pass instead: one ray per fragment from textures, in the cube's texture space.
#include "techniques/cell_complex/cell_complex_common.glsl"

#ifdef RL_PROBE
#include "harness/glsl/probe_io.glsl"

void main() {
  vec4 origin_q, direction_q;
  rl_probe_ray(origin_q, direction_q);
  vec3 origin = origin_q.xyz, direction = direction_q.xyz;
  float n = float(rl_cell_n);
  float scale = length(direction) * n;  // grid units per unit of the probe's t
  float t_before;
  float t = scale > 0.0 ? rl_cell_search(origin * n, direction * n / scale, t_before) : -1.0;
  vec3 hit = origin + direction * (t / scale);
  rl_probe_write(t >= 0.0 ? t / scale : 0.0, hit.xy, hit.z, 0.0, t >= 0.0, rl_fetches);
}
#else
#include "harness/glsl/shading.glsl"

in vec3 v_tex;

uniform vec3 rl_eye;
uniform vec3 rl_light;
uniform vec3 rl_eye_texture;
uniform mat4 rl_view_projection;
uniform mat4 rl_world_from_texture;
uniform mat3 rl_normal_from_texture;  // inverse transpose of its linear part
uniform vec3 rl_cell_albedo;          // a hit in a black cell (the surface on its face)

#include "harness/glsl/gbuffer_outputs.glsl"

void main() {
  float n = float(rl_cell_n);
  vec3 d = normalize(v_tex - rl_eye_texture);
  vec3 o = v_tex * n;
  float t_before;
  float t = rl_cell_search(o, d, t_before);
  if (t < 0.0) RL_DISCARD;
  vec3 g = o + d * t;
  vec3 hit_tex = g / n;
  vec3 hit_world = (rl_world_from_texture * vec4(hit_tex, 1.0)).xyz;
  vec4 hit_clip = rl_view_projection * vec4(hit_world, 1.0);
  gl_FragDepth = clamp(0.5 * hit_clip.z / hit_clip.w + 0.5, 0.0, 1.0);

  // Normal and colour at the hit's face point (Section 3.5.2, step 4), read just outside the
  // surface: the last inside sample may lie across a cell face in a black cell, which has no
  // maps (only where that fails, at the inside sample).
  vec3 V = normalize(hit_world - rl_eye);
  vec3 tn = vec3(0.0);
  vec3 albedo = rl_cell_albedo;
  RlCellPoint p = rl_cell_point(o + d * t_before);
  if (p.state != RL_GREY) p = rl_cell_point(g);
  if (p.state == RL_GREY) {
    rl_fetches += 2;
    tn = textureLod(rl_cell_normal, p.coord, 0.0).rgb * 2.0 - 1.0;
    albedo = textureLod(rl_cell_color, p.coord, 0.0).rgb;
  }
  vec3 nw = rl_normal_from_texture * tn;
  nw = dot(nw, nw) > 0.0 ? normalize(nw) : -V;
  if (dot(nw, V) > 0.0) nw = -nw;  // facing the viewer, as the truth's mesh normals
  vec3 to_light = normalize(rl_light - hit_world);
  o_color = vec4(rl_shade(albedo, nw, to_light, -V, false), 1.0);
#ifdef RL_GBUFFER
  o_position = vec4(hit_world, 1.0);
  o_normal = vec4(nw, 0.0);
  o_hit = vec4(hit_tex.xy, 0.0, float(rl_fetches));
  o_aux = vec4(1.0, 0.0, dot(rl_ambient * albedo, vec3(1.0 / 3.0)), 0.0);
#endif
  rl_count_fragment();
}
#endif
