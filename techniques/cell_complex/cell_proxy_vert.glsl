// The proxy of a cell complex: faces of grey cells that border white cells or the grid,
// in the cube's texture space, placed in the world by the scene's planar base.
layout(location = 0) in vec3 a_tex;

uniform mat4 rl_view_projection;
uniform mat4 rl_world_from_texture;

out vec3 v_tex;

void main() {
  v_tex = a_tex;
  gl_Position = rl_view_projection * (rl_world_from_texture * vec4(a_tex, 1.0));
}
