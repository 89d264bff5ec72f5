// Plain triangle-mesh objects (scene/scene_objects.h): world position, normal, albedo.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_albedo;

uniform mat4 rl_view_projection;

out vec3 v_world;
out vec3 v_normal;
out vec3 v_albedo;

void main() {
  v_world = a_position;
  v_normal = a_normal;
  v_albedo = a_albedo;
  gl_Position = rl_view_projection * vec4(a_position, 1.0);
}
