// A grey cell's configuration and projection (Apaza & Andujar, Section 3.2): which of its faces
// form the domain for each of the ten cases, the projection that maps the cell onto them, and
// the projection lines of points and of face texels.
#include <algorithm>
#include <cmath>

#include "relief/cell_complex.h"

namespace rl {
namespace {

glm::dvec3 axis_vector(int a) {
  glm::dvec3 v(0);
  v[a] = 1;
  return v;
}

// Outward normal of face f.
glm::dvec3 face_normal(int f) {
  return axis_vector(f / 2) * (f % 2 ? 1.0 : -1.0);
}

glm::dvec3 face_centre(int f) {
  glm::dvec3 c(0.5);
  c[f / 2] = f % 2;
  return c;
}

// The projection line's inner end for a point q on it (or on the cell's boundary).
glm::dvec3 inner_point(const CellProjection& p, const glm::dvec3& q) {
  using T = CellProjection::Type;
  switch (p.type) {
    case T::Perspective:
      return p.point;
    case T::Axial: {
      glm::dvec3 foot = p.point;
      foot[p.axis] = q[p.axis];
      return foot;
    }
    case T::Planar: {
      glm::dvec3 on = q;
      on[p.axis] = p.point[p.axis];
      return on;
    }
    case T::Parallel: {
      glm::dvec3 far = q;
      far[p.axis / 2] = p.axis % 2 ? 0.0 : 1.0;
      return far;
    }
  }
  return p.point;
}

}  // namespace

const char* cell_case_name(CellCase c) {
  static const char* names[] = {"0", "1", "2a", "2b", "3a", "3b", "4a", "4b", "5", "6"};
  return names[int(c)];
}

const char* projection_type_name(CellProjection::Type t) {
  static const char* names[] = {"perspective", "axial", "planar", "parallel"};
  return names[int(t)];
}

CellConfiguration configure_cell(uint8_t internal_mask) {
  using T = CellProjection::Type;
  const unsigned internal = internal_mask & 63u, external = ~internal_mask & 63u;
  CellConfiguration c;
  c.domain_mask = uint8_t(external);
  CellProjection& p = c.projection;
  auto faces_of = [](unsigned m) {
    std::vector<int> f;
    for (int i = 0; i < 6; ++i)
      if ((m >> i) & 1u) f.push_back(i);
    return f;
  };
  const std::vector<int> in = faces_of(internal), ex = faces_of(external);
  switch (in.size()) {
    case 0:  // all external: perspective from the centre
      c.base_case = CellCase::C0;
      p = {T::Perspective, glm::dvec3(0.5), 0};
      break;
    case 1:  // one internal face F: perspective from F's middle
      c.base_case = CellCase::C1;
      p = {T::Perspective, face_centre(in[0]), 0};
      break;
    case 2:
      if (in[0] / 2 == in[1] / 2) {  // two opposite internal faces: axial through their middles
        c.base_case = CellCase::C2b;
        p = {T::Axial, glm::dvec3(0.5), in[0] / 2};
      } else {  // one internal edge: perspective from its middle
        c.base_case = CellCase::C2a;
        glm::dvec3 m(0.5);
        m[in[0] / 2] = in[0] % 2;
        m[in[1] / 2] = in[1] % 2;
        p = {T::Perspective, m, 0};
      }
      break;
    case 3: {
      int pair_axis = -1;
      for (int a = 0; a < 3; ++a)
        if (((internal >> (2 * a)) & 3u) == 3u) pair_axis = a;
      if (pair_axis >= 0) {
        // Two opposite internal faces and the one between them: two internal edges, parallel;
        // the axis joins their middles, across the middle face, along the pair's normal.
        c.base_case = CellCase::C3a;
        int middle = -1;
        for (int f : in)
          if (f / 2 != pair_axis) middle = f;
        glm::dvec3 a(0.5);
        a[middle / 2] = middle % 2;
        p = {T::Axial, a, pair_axis};
      } else {  // three internal faces meeting at a vertex: perspective from it
        c.base_case = CellCase::C3b;
        glm::dvec3 v(0.5);
        for (int f : in) v[f / 2] = f % 2;
        p = {T::Perspective, v, 0};
      }
      break;
    }
    case 4:
      if (ex[0] / 2 == ex[1] / 2) {  // two parallel external faces: the plane between them
        c.base_case = CellCase::C4a;
        p = {T::Planar, glm::dvec3(0.5), ex[0] / 2};
      } else {  // one external edge: axial from the opposite edge
        c.base_case = CellCase::C4b;
        const int a1 = ex[0] / 2, a2 = ex[1] / 2, along = 3 - a1 - a2;
        glm::dvec3 a(0.5);
        a[a1] = 1 - ex[0] % 2;
        a[a2] = 1 - ex[1] % 2;
        p = {T::Axial, a, along};
      }
      break;
    case 5:  // one external face: parallel along its normal
      c.base_case = CellCase::C5;
      p = {T::Parallel, glm::dvec3(0.5), ex[0]};
      break;
    default:  // all internal (an interior grey cell): perspective from the centre, onto all six
      c.base_case = CellCase::C6;
      p = {T::Perspective, glm::dvec3(0.5), 0};
      c.domain_mask = 63;
      break;
  }
  return c;
}

glm::dvec3 face_point(int face, glm::dvec2 st) {
  const int a = face / 2;
  glm::dvec3 q;
  q[a] = face % 2;
  q[(a + 1) % 3] = st.x;
  q[(a + 2) % 3] = st.y;
  return q;
}

glm::dvec2 face_coords(int face, const glm::dvec3& q) {
  const int a = face / 2;
  return {q[(a + 1) % 3], q[(a + 2) % 3]};
}

CellLine face_line(const CellProjection& p, int face, glm::dvec2 st) {
  CellLine l;
  l.face = face;
  l.on_face = face_point(face, st);
  l.inner = inner_point(p, l.on_face);
  l.length = glm::length(l.on_face - l.inner);
  l.along = 0;
  return l;
}

CellLine project_in_cell(const CellProjection& p, uint8_t domain_mask, const glm::dvec3& q) {
  using T = CellProjection::Type;
  CellLine l;
  l.inner = inner_point(p, q);
  glm::dvec3 dir;
  if (p.type == T::Planar) {
    dir = axis_vector(p.axis) * (q[p.axis] >= p.point[p.axis] ? 1.0 : -1.0);
  } else if (p.type == T::Parallel) {
    dir = face_normal(p.axis);
  } else {
    dir = q - l.inner;
  }
  if (glm::dot(dir, dir) < 1e-24) {
    // q is the centre (or on the axis): every line passes through it; take the one towards the
    // first domain face, perpendicular to an axial projection's axis.
    int f = 0;
    while (f < 5 && !((domain_mask >> f) & 1u)) ++f;
    dir = face_normal(f);
  }
  double s = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
    if (dir[a] != 0) s = std::min(s, ((dir[a] > 0 ? 1.0 : 0.0) - q[a]) / dir[a]);
  s = std::max(s, 0.0);
  // The exit face; at an edge or corner a domain face wins the tie.
  int face = -1;
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0) continue;
    const double sa = ((dir[a] > 0 ? 1.0 : 0.0) - q[a]) / dir[a];
    if (sa > s + 1e-12) continue;
    const int f = 2 * a + (dir[a] > 0 ? 1 : 0);
    if (face < 0 || (((domain_mask >> f) & 1u) && !((domain_mask >> face) & 1u))) face = f;
  }
  l.face = face;
  l.on_face = glm::clamp(q + dir * s, 0.0, 1.0);
  l.on_face[face / 2] = face % 2;
  l.along = glm::length(l.on_face - q);
  l.length = glm::length(l.on_face - l.inner);
  return l;
}

bool triangle_overlaps_box(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                           const glm::dvec3& box_lo, const glm::dvec3& box_hi) {
  const glm::dvec3 centre = 0.5 * (box_lo + box_hi), half = 0.5 * (box_hi - box_lo);
  const glm::dvec3 v[3] = {a - centre, b - centre, c - centre};
  // The box's face normals: the triangle's bounding box against the box.
  for (int k = 0; k < 3; ++k) {
    const double lo = std::min({v[0][k], v[1][k], v[2][k]});
    const double hi = std::max({v[0][k], v[1][k], v[2][k]});
    if (lo > half[k] || hi < -half[k]) return false;
  }
  const glm::dvec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  // The triangle's plane.
  const glm::dvec3 n = glm::cross(e[0], e[1]);
  const double r = half.x * std::abs(n.x) + half.y * std::abs(n.y) + half.z * std::abs(n.z);
  if (std::abs(glm::dot(n, v[0])) > r) return false;
  // Edge x box-axis cross products.
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 axis = glm::cross(axis_vector(k), e[i]);
      if (glm::dot(axis, axis) < 1e-30) continue;
      const double p0 = glm::dot(axis, v[0]), p1 = glm::dot(axis, v[1]), p2 = glm::dot(axis, v[2]);
      const double rad =
          half.x * std::abs(axis.x) + half.y * std::abs(axis.y) + half.z * std::abs(axis.z);
      if (std::min({p0, p1, p2}) > rad || std::max({p0, p1, p2}) < -rad) return false;
    }
  return true;
}

}  // namespace rl
