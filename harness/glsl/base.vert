// Base surface: world position, texture coordinate and the mapping's tangent frame.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec2 a_uv;
layout(location = 2) in vec3 a_dpdu;
layout(location = 3) in vec3 a_dpdv;
layout(location = 4) in vec3 a_normal;
layout(location = 5) in float a_entry_depth;
layout(location = 6) in vec2 a_curvature;  // quadric (A, B) of the base (chapter 5)

uniform mat4 rl_view_projection;

out vec3 v_world;
out vec2 v_uv;
out vec3 v_dpdu;
out vec3 v_dpdv;
out vec3 v_normal;
out float v_entry_depth;
out vec2 v_curvature;

void main() {
  v_world = a_position;
  v_uv = a_uv;
  v_dpdu = a_dpdu;
  v_dpdv = a_dpdv;
  v_normal = a_normal;
  v_entry_depth = a_entry_depth;
  v_curvature = a_curvature;
  gl_Position = rl_view_projection * vec4(a_position, 1.0);
}
