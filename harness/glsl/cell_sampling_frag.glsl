// Section 3.3.2's fragment shader: a fragment is a surface point q (interpolated from the mesh
// triangle's corners) whose projection covers the texel; it writes its distance from the face
// point P' as a share of the projection line's length inside the cell, which is also its depth,
// "so that OpenGL's depth test will discard occluded samples": the texel keeps the surface point
// nearest the face, and its normal beside it. Points outside the cell, or behind the projection's
// centre, axis or plane (whose lines leave through another face), are not the face's.
#include "harness/glsl/cell_sampling_projection.glsl"

in vec3 g_local;
flat in vec3 g_normal;
layout(location = 0) out float o_distance;
layout(location = 1) out vec4 o_normal;  // the surface point's (its triangle's), unit
uniform float rl_res;

void main() {
  const float slack = 1e-5;  // the cell's boundary, up to rounding
  if (any(lessThan(g_local, vec3(-slack))) || any(greaterThan(g_local, vec3(1.0 + slack)))) discard;
  if (rl_projection != 3 && rl_projection_reach(g_local) <= 0.0) discard;
  vec3 on_face = rl_face_point(gl_FragCoord.xy / rl_res);
  float d = clamp(distance(g_local, on_face) / rl_line_length(on_face), 0.0, 1.0);
  o_distance = d;
  o_normal = vec4(g_normal, 0.0);
  gl_FragDepth = d;
}
