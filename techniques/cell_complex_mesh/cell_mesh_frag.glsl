// Geometry-based rendering of a cell complex: the maps' normals and colours interpolated over
// the reconstructed triangles by the rasteriser (no texture fetch per pixel).
#include "harness/glsl/shading.glsl"

in vec3 v_tex;
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;

uniform vec3 rl_eye;
uniform vec3 rl_light;

#include "harness/glsl/gbuffer_outputs.glsl"

void main() {
  vec3 V = normalize(v_world - rl_eye);
  vec3 n = dot(v_normal, v_normal) > 0.0 ? normalize(v_normal) : -V;
#ifndef RL_NORMALS_AS_GIVEN
  if (dot(n, V) > 0.0) n = -n;  // facing the viewer, as the truth's mesh normals
#endif  // (heightfield_mesh: the map's normals, which a relief's truth does not turn)
  vec3 to_light = normalize(rl_light - v_world);
  o_color = vec4(rl_shade(v_color, n, to_light, -V, false), 1.0);
#ifdef RL_GBUFFER
  o_position = vec4(v_world, 1.0);
  o_normal = vec4(n, 0.0);
  o_hit = vec4(v_tex.xy, 0.0, 0.0);
  o_aux = vec4(1.0, 0.0, dot(rl_ambient * v_color, vec3(1.0 / 3.0)), 0.0);
#endif
  rl_count_fragment();  // a rasterised triangle: no fetch, no search
}
