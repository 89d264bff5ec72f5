// Plain objects, shaded like the relief (no shadows), into the same G-buffer; layer -1 in the
// hit channel marks them (the truth writes the same: truth/objects_truth.cpp).
#include "harness/glsl/shading.glsl"

in vec3 v_world;
in vec3 v_normal;
in vec3 v_albedo;

uniform vec3 rl_eye;
uniform vec3 rl_light;

#include "harness/glsl/gbuffer_outputs.glsl"

void main() {
  vec3 n = normalize(v_normal);
  vec3 to_light = normalize(rl_light - v_world);
  o_color = vec4(rl_shade(v_albedo, n, to_light, normalize(rl_eye - v_world), false), 1.0);
#ifdef RL_GBUFFER
  o_position = vec4(v_world, 1.0);
  o_normal = vec4(n, 0.0);
  o_hit = vec4(0.0, 0.0, -1.0, 0.0);
  o_aux = vec4(1.0, 0.0, dot(rl_ambient * v_albedo, vec3(1.0 / 3.0)), 0.0);
#endif
}
