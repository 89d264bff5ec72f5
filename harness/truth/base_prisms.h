#pragma once
// The shell a relief on a curved base occupies, one prism per base triangle, in the prism's own
// parameters: the point at barycentrics (b1, b2) of triangle t (b0 = 1 - b1 - b2), s world
// units inward along the interpolated unit normal,
//
//   X(b, s) = P(b) - s N(b) / |N(b)|,   P, N and uv linear in b,
//
// as the rasteriser interpolates the base mesh. The relief the map stands for is s = depth x
// d(uv(b)); a ray is mapped into these parameters point by point (locate) and, since uv is
// affine in b, into the map's texture space (u, v, s / depth) where the map's own exact solvers
// work. Adjacent prisms share a side where their triangles share an edge whose positions and
// normals agree (to a billionth of the mesh's size); a uv seam (other uvs) is such an edge.
#include <vector>

#include <glm/glm.hpp>

#include "scene/base_mesh.h"

namespace rl {

struct PrismPoint {
  unsigned triangle = 0;
  double b1 = 0, b2 = 0;  // barycentrics of the base triangle (may lie outside it)
  double s = 0;           // world distance inward along the unit normal
};

class BasePrisms {
 public:
  // `texels`: texels per unit of texture coordinate (the map's size; a meta-relief's finest).
  BasePrisms(const BaseMesh& base, const glm::dvec2& texels);

  size_t size() const { return prisms_.size(); }
  // False for a triangle of no area (a sphere's pole cap): it has no prism.
  bool usable(unsigned t) const { return prisms_[t].usable; }
  glm::dvec3 point(unsigned t, double b1, double b2, double s) const;
  glm::dvec3 unit_normal(unsigned t, double b1, double b2) const;
  glm::dvec2 uv(unsigned t, double b1, double b2) const;
  // The shading frame there, as the shaders build it (uv_frame of the interpolated normal and
  // mapping axes).
  void frame(unsigned t, double b1, double b2, glm::dvec3& tangent, glm::dvec3& bitangent) const;
  // World point x in triangle t's parameters (Newton's method from the flat prism's solution,
  // to double rounding); false when it does not converge (x far outside the shell).
  bool locate(const glm::dvec3& x, unsigned t, PrismPoint& p) const;
  // The prism across triangle t's edge opposite its vertex e (where b_e = 0), or -1: a border,
  // an edge where the normals split, or one shared by more than two triangles.
  int neighbour(unsigned t, int e) const { return prisms_[t].neighbour[e]; }
  // World length of one texel on triangle t (the shortest over its edges' directions).
  double texel_world(unsigned t) const { return prisms_[t].texel_world; }
  // Its longest edge (world).
  double extent(unsigned t) const { return prisms_[t].extent; }
  // Welded ids of triangle t's vertices: equal where positions and normals agree
  // to a billionth of the mesh's size.
  const glm::uvec3& welded(unsigned t) const { return prisms_[t].welded; }
  // Triangle t's corner c (0, 1, 2: b0, b1, b2 = 1) as the base mesh gives it, bit for bit.
  const glm::dvec3& corner(unsigned t, int c) const { return prisms_[t].corner[c]; }
  const glm::dvec3& corner_normal(unsigned t, int c) const { return prisms_[t].corner_normal[c]; }
  // +1 where the triangle winds counter-clockwise seen from its normals' side, else -1.
  double winding(unsigned t) const { return prisms_[t].winding; }

 private:
  struct Prism {
    glm::dvec3 p0{0}, e1{0}, e2{0};  // P(b) = p0 + b1 e1 + b2 e2
    glm::dvec3 n0{0}, m1{0}, m2{0};  // N(b) = n0 + b1 m1 + b2 m2 (unnormalised)
    glm::dvec2 uv0{0}, duv1{0}, duv2{0};
    glm::dmat3 flat_inverse{1.0};  // (b1, b2, s) of the prism with N = n0, from x - p0
    glm::uvec3 welded{0};
    glm::dvec3 corner[3], corner_normal[3], dpdu[3], dpdv[3];
    double winding = 1;
    int neighbour[3] = {-1, -1, -1};
    double texel_world = 0, extent = 0;
    bool usable = false;
  };
  void link_neighbours();

  std::vector<Prism> prisms_;
};

}  // namespace rl
