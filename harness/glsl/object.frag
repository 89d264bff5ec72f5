// Plain objects, shaded like the relief, into the same G-buffer; layer -1 in the hit channel
// marks them (the truth writes the same: truth/objects_truth.cpp). In shadow only where the
// scene asks for scene_shadows; drawn as a shadow caster (depth only) into its shadow map.
#include "harness/glsl/shading.glsl"
#ifdef RL_SCENE_SHADOWS
#include "harness/glsl/shadow_map.glsl"
#endif

in vec3 v_world;
in vec3 v_normal;
in vec3 v_albedo;

uniform vec3 rl_eye;
uniform vec3 rl_light;

#include "harness/glsl/gbuffer_outputs.glsl"

void main() {
#ifdef RL_SHADOW_CASTER
  o_color = vec4(0.0);
  return;
#endif
  vec3 n = normalize(v_normal);
  vec3 to_light = normalize(rl_light - v_world);
  bool in_shadow = false;
#ifdef RL_SCENE_SHADOWS
  in_shadow = rl_in_scene_shadow(v_world, n);
#endif
  o_color = vec4(rl_shade(v_albedo, n, to_light, normalize(rl_eye - v_world), in_shadow), 1.0);
#ifdef RL_GBUFFER
  o_position = vec4(v_world, 1.0);
  o_normal = vec4(n, in_shadow ? 1.0 : 0.0);
  o_hit = vec4(0.0, 0.0, -1.0, 0.0);
  o_aux = vec4(1.0, 0.0, dot(rl_ambient * v_albedo, vec3(1.0 / 3.0)), 0.0);
#endif
}
