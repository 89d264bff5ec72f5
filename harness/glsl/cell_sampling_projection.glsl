// One grey cell's projection onto the domain face being sampled (relief/cell_complex.h: faces
// f = 2 axis + side; a face's map indexed by (q[(axis + 1) % 3], q[(axis + 2) % 3])), for the
// geometry and fragment shaders of the GPU sampling of Section 3.3.2. Cell-local coordinates.
uniform int rl_face;              // the domain face, 0-5
uniform int rl_projection;        // 0 perspective, 1 axial, 2 planar, 3 parallel
uniform vec3 rl_projection_point; // perspective: centre; axial: a point of the axis; planar: on the plane
uniform int rl_projection_axis;   // axial: the axis; planar: the plane's normal axis

int rl_face_axis() {
  return rl_face / 2;
}

float rl_face_side() {
  return float(rl_face % 2);
}

// The inner end of the projection line through q, for the central projections: the centre
// (perspective), or the axis' foot at q (axial).
vec3 rl_projection_inner(vec3 q) {
  vec3 inner = rl_projection_point;
  if (rl_projection == 1) inner[rl_projection_axis] = q[rl_projection_axis];
  return inner;
}

// q's distance from the inner end along the face's axis, as a share of the face's: 1 on the
// face, in (0, 1) between, <= 0 where q lies behind the centre or axis (or the plane), whose
// lines leave through another face.
float rl_projection_reach(vec3 q) {
  int a = rl_face_axis();
  float c = rl_projection == 3 ? 1.0 - rl_face_side() : rl_projection_point[a];
  return (q[a] - c) / (rl_face_side() - c);
}

// The face point P' of face coordinates st, and the length of its projection line inside the
// cell (from P' to its inner end), as relief/cell_geometry.cpp draws them.
vec3 rl_face_point(vec2 st) {
  int a = rl_face_axis();
  vec3 p;
  p[a] = rl_face_side();
  p[(a + 1) % 3] = st.x;
  p[(a + 2) % 3] = st.y;
  return p;
}

float rl_line_length(vec3 on_face) {
  if (rl_projection == 3) return 1.0;
  if (rl_projection == 2) return abs(rl_face_side() - rl_projection_point[rl_face_axis()]);
  return length(on_face - rl_projection_inner(on_face));
}
