#include "scene/clipped_frustum.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace rl {
namespace {

using Polygon = std::vector<glm::dvec3>;

// A half-space n . x <= d.
struct HalfSpace {
  glm::dvec3 n;
  double d;
  double side(const glm::dvec3& x) const { return glm::dot(n, x) - d; }
};

// Sutherland-Hodgman: the part of convex polygon `p` inside `h`.
Polygon clip(const Polygon& p, const HalfSpace& h) {
  Polygon out;
  for (size_t i = 0; i < p.size(); ++i) {
    const glm::dvec3& a = p[i];
    const glm::dvec3& b = p[(i + 1) % p.size()];
    const double sa = h.side(a), sb = h.side(b);
    if (sa <= 0) out.push_back(a);
    if ((sa < 0 && sb > 0) || (sa > 0 && sb < 0)) out.push_back(a + (b - a) * (sa / (sa - sb)));
  }
  return out;
}

glm::dvec3 newell_normal(const Polygon& p) {
  glm::dvec3 n(0);
  for (size_t i = 0; i < p.size(); ++i) n += glm::cross(p[i], p[(i + 1) % p.size()]);
  return n;
}

// The six faces of a hexahedron given its 8 corners (bit 0: x, bit 1: y, bit 2: z), each as a
// polygon.
std::array<Polygon, 6> hexahedron_faces(const std::array<glm::dvec3, 8>& c) {
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::array<Polygon, 6> out;
  for (int f = 0; f < 6; ++f)
    for (int k : faces[f]) out[size_t(f)].push_back(c[size_t(k)]);
  return out;
}

// The half-spaces the faces bound, normals pointing away from `inside`.
std::array<HalfSpace, 6> half_spaces(const std::array<Polygon, 6>& faces,
                                     const glm::dvec3& inside) {
  std::array<HalfSpace, 6> out;
  for (size_t f = 0; f < 6; ++f) {
    glm::dvec3 n = glm::normalize(newell_normal(faces[f]));
    double d = glm::dot(n, faces[f][0]);
    if (glm::dot(n, inside) > d) n = -n, d = -d;  // outward
    out[f] = {n, d};
  }
  return out;
}

// The faces of `a` clipped by every half-space of `b`, less those lying in a plane of `b`
// (where both solids share a face, `b`'s own copy stands for it).
void add_clipped(const std::array<Polygon, 6>& a, const std::array<HalfSpace, 6>& b,
                 bool skip_coplanar, std::vector<Polygon>& out) {
  for (const Polygon& face : a) {
    bool coplanar = false;
    for (const HalfSpace& h : b) {
      double worst = 0;
      for (const glm::dvec3& v : face) worst = std::max(worst, std::abs(h.side(v)));
      coplanar |= worst < 1e-12;
    }
    if (skip_coplanar && coplanar) continue;
    Polygon p = face;
    for (const HalfSpace& h : b) {
      HalfSpace loose = h;
      loose.d += 1e-12;  // a face on b's boundary stays
      p = clip(p, loose);
      if (p.size() < 3) break;
    }
    if (p.size() >= 3 && glm::length(newell_normal(p)) > 1e-14) out.push_back(p);
  }
}

}  // namespace

bool relief_affine_bounds(const ReliefMap& map, const ReverseProjection& projection,
                          bool empty_floor, AffineBox& box) {
  glm::dvec3 lo(1e30), hi(-1e30);
  for (int j = 0; j < map.height; ++j)
    for (int i = 0; i < map.width; ++i) {
      const double depth = map.relief[size_t(j) * map.width + i].a;
      if (empty_floor && depth >= 1.0 - 1e-6) continue;
      const double u0 = std::max(0.0, (i - 1.0) / map.width),
                   u1 = std::min(1.0, (i + 2.0) / map.width);
      const double v0 = std::max(0.0, (j - 1.0) / map.height),
                   v1 = std::min(1.0, (j + 2.0) / map.height);
      for (int c = 0; c < 8; ++c) {
        const glm::dvec3 a = projection.affine_from_texture(
            {c & 1 ? u1 : u0, c & 2 ? v1 : v0, c & 4 ? 1.0 : std::clamp(depth, 0.0, 1.0)});
        lo = glm::min(lo, a);
        hi = glm::max(hi, a);
      }
    }
  if (lo.x > hi.x) return false;
  box = {lo, hi};
  return true;
}

std::vector<std::vector<glm::dvec3>> clipped_frustum_faces(const ReverseProjection& projection,
                                                           const AffineBox& box) {
  std::array<glm::dvec3, 8> frustum, cube;
  for (int c = 0; c < 8; ++c) {
    frustum[size_t(c)] =
        projection.affine_from_texture({double(c & 1), double((c >> 1) & 1), double((c >> 2) & 1)});
    cube[size_t(c)] = {c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y,
                       c & 4 ? box.hi.z : box.lo.z};
  }
  const std::array<Polygon, 6> frustum_faces = hexahedron_faces(frustum);
  const std::array<Polygon, 6> cube_faces = hexahedron_faces(cube);
  glm::dvec3 f_mid(0), c_mid(0);
  for (int c = 0; c < 8; ++c) f_mid += frustum[size_t(c)] / 8.0, c_mid += cube[size_t(c)] / 8.0;
  std::vector<Polygon> faces;
  add_clipped(frustum_faces, half_spaces(cube_faces, c_mid), false, faces);
  add_clipped(cube_faces, half_spaces(frustum_faces, f_mid), true, faces);
  // Counter-clockwise seen from outside in world space: affine space is texture space, whose
  // depth runs opposite to the world's up, so there the winding turns each face's normal
  // towards the solid's middle.
  glm::dvec3 mid(0);
  size_t count = 0;
  for (const Polygon& p : faces)
    for (const glm::dvec3& v : p) mid += v, ++count;
  if (count) mid /= double(count);
  for (Polygon& p : faces) {
    glm::dvec3 centre(0);
    for (const glm::dvec3& v : p) centre += v / double(p.size());
    if (glm::dot(newell_normal(p), centre - mid) > 0) std::reverse(p.begin(), p.end());
  }
  return faces;
}

}  // namespace rl
