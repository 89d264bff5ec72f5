// Section 3.3.2's geometry shader: each mesh triangle that may cross the cell, projected onto the
// domain face being sampled. Perspective projections map it onto a triangle, exactly: it is
// emitted in homogeneous coordinates whose w is the projection's divisor, so the rasteriser
// interpolates the cell-local point perspective-correctly. Planar and parallel ones are
// orthographic. The axial projection maps straight edges onto curves (Figure 3): with
// rl_subdivide_texels > 0, a triangle whose projected edges are longer than that many face texels
// is cut first, "uniformly subdividing the edges longer than a user-defined threshold". A
// geometry shader's output is bounded, so the cut is in two levels: RL_CELL_SPLITS^2 invocations
// each take one of the triangle's m x m first pieces (m at most RL_CELL_SPLITS) and cut it into
// k x k (k at most RL_CELL_PIECES): edges of up to 40 x the threshold are cut to it.
#include "harness/glsl/cell_sampling_projection.glsl"

#ifndef RL_CELL_SPLITS
#define RL_CELL_SPLITS 1
#endif
#define RL_CELL_PIECES 8
// k^2 + 2k vertices for k x k pieces, as strips of rows.
layout(triangles, invocations = RL_CELL_SPLITS * RL_CELL_SPLITS) in;
layout(triangle_strip, max_vertices = 80) out;
in vec3 v_position[];
out vec3 g_local;        // the cell-local point a fragment stands for
flat out vec3 g_normal;  // its triangle's: the CPU's maps hold the hit triangle's (Embree's Ng)

uniform vec3 rl_cell_origin;  // the cell's lowest corner, in cells
uniform float rl_grid;        // N
uniform float rl_res;         // texels per face side
uniform float rl_subdivide_texels;

// Where on the face (its [0, 1]^2 as clip space [-1, 1]^2) q projects, with w the divisor.
vec4 rl_face_clip(vec3 q) {
  int a = rl_face_axis(), i = (a + 1) % 3, j = (a + 2) % 3;
  vec3 c = rl_projection_point;
  if (rl_projection == 0) {
    // P' = c + (q - c) / w, w = reach: linear in q, so the whole map is projective.
    float w = rl_projection_reach(q);
    vec2 st_w = vec2(c[i] * w + q[i] - c[i], c[j] * w + q[j] - c[j]);
    return vec4(2.0 * st_w - w, 0.0, w);
  }
  vec2 st = vec2(q[i], q[j]);
  if (rl_projection == 1) {
    // Across the axis a central projection, along it none.
    int across = i == rl_projection_axis ? j : i;
    float reach = rl_projection_reach(q);
    float moved = c[across] + (q[across] - c[across]) / max(reach, 1e-6);
    st = across == i ? vec2(moved, st.y) : vec2(st.x, moved);
    // Behind the axis: its lines leave through another face; the fragment stage discards it.
  }
  return vec4(2.0 * st - 1.0, 0.0, 1.0);
}

// n: the mesh triangle's normal, whatever piece of it is drawn.
void rl_emit(vec3 q, vec3 n) {
  g_local = q;
  g_normal = n;
  gl_Position = rl_face_clip(q);
  EmitVertex();
}

// How long the triangle's longest projected edge is, in face texels.
float rl_projected_texels(vec3 q0, vec3 q1, vec3 q2) {
  vec4 c0 = rl_face_clip(q0), c1 = rl_face_clip(q1), c2 = rl_face_clip(q2);
  float longest = max(max(distance(c0.xy, c1.xy), distance(c1.xy, c2.xy)), distance(c2.xy, c0.xy));
  return 0.5 * longest * rl_res;
}

// Cuts into k x k pieces, emitted as strips of rows of the barycentric grid.
void rl_emit_pieces(vec3 q0, vec3 q1, vec3 q2, int k, vec3 n) {
  vec3 e1 = (q1 - q0) / float(k), e2 = (q2 - q0) / float(k);
  for (int r = 0; r < k; ++r) {
    for (int i = 0; i < k - r; ++i) {
      rl_emit(q0 + e1 * float(i) + e2 * float(r), n);
      rl_emit(q0 + e1 * float(i) + e2 * float(r + 1), n);
    }
    rl_emit(q0 + e1 * float(k - r) + e2 * float(r), n);
    EndPrimitive();
  }
}

// First piece `id` of m x m (rows of upward and downward triangles) of q0 q1 q2; false if none.
bool rl_first_piece(int id, int m, vec3 q[3], out vec3 piece[3]) {
  vec3 e1 = (q[1] - q[0]) / float(m), e2 = (q[2] - q[0]) / float(m);
  for (int r = 0; r < m; ++r) {
    int in_row = 2 * (m - r) - 1;
    if (id < in_row) {
      int i = id / 2;
      vec3 a = q[0] + e1 * float(i) + e2 * float(r);
      piece[0] = (id % 2 == 0) ? a : a + e1;
      piece[1] = (id % 2 == 0) ? a + e1 : a + e1 + e2;
      piece[2] = a + e2;
      return true;
    }
    id -= in_row;
  }
  return false;
}

void main() {
  vec3 q[3];
  for (int v = 0; v < 3; ++v) q[v] = v_position[v] * rl_grid - rl_cell_origin;
  // Embree's geometric normal of triangle (v0, v1, v2), (v1 - v0) x (v2 - v0), here unit.
  vec3 n = normalize(cross(v_position[1] - v_position[0], v_position[2] - v_position[0]));
  bool cut = rl_projection == 1 && rl_subdivide_texels > 0.0;
  float pieces = cut ? rl_projected_texels(q[0], q[1], q[2]) / rl_subdivide_texels : 1.0;
  int m = clamp(int(ceil(pieces / float(RL_CELL_PIECES))), 1, RL_CELL_SPLITS);
  vec3 piece[3];
  if (!rl_first_piece(gl_InvocationID, m, q, piece)) return;
  int k = clamp(int(ceil(pieces / float(m))), 1, RL_CELL_PIECES);
  rl_emit_pieces(piece[0], piece[1], piece[2], k, n);
}
