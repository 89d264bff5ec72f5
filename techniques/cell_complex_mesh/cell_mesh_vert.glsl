// Geometry-based rendering of a cell complex (Section 3.5.1): the unprojected texels, in the
// cube's texture space, placed in the world by the scene's planar base.
layout(location = 0) in vec3 a_tex;
layout(location = 1) in vec3 a_normal;  // texture space
layout(location = 2) in vec3 a_color;

uniform mat4 rl_view_projection;
uniform mat4 rl_world_from_texture;
uniform mat3 rl_normal_from_texture;

out vec3 v_tex;
out vec3 v_world;
out vec3 v_normal;
out vec3 v_color;

void main() {
  v_tex = a_tex;
  v_world = (rl_world_from_texture * vec4(a_tex, 1.0)).xyz;
  v_normal = rl_normal_from_texture * a_normal;
  v_color = a_color;
  gl_Position = rl_view_projection * vec4(v_world, 1.0);
}
