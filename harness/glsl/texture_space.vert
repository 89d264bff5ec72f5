// Geometry given in the relief's texture space (u, v, depth) -- a cell complex's proxy faces, a
// heightfield object's cube, depth slices -- placed in the world by the scene's planar base
// (rl_world_from_texture, set_texture_space_uniforms).
layout(location = 0) in vec3 a_tex;

uniform mat4 rl_view_projection;
uniform mat4 rl_world_from_texture;

out vec3 v_tex;

void main() {
  v_tex = a_tex;
  gl_Position = rl_view_projection * (rl_world_from_texture * vec4(a_tex, 1.0));
}
