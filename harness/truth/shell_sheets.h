#pragma once
// The curved-base truth's front end (truth/displaced_truth.h): a sheet of flat triangles that
// lies on the outer side of the relief everywhere, so that a ray cannot meet the relief before
// it has entered the sheet, and that Embree traces.
//
// Each base triangle is split n x n. A sheet vertex at barycentrics b_k sits at
// P(b_k) - depth c_k N(b_k) / |N(b_k)|, c_k the least depth of the map over the uv footprints
// (each padded by a texel) of every sub-triangle around the vertex. Along the fibre of any b in
// a sub-triangle the flat sheet's point lies at most depth x max c_k <= depth x d(uv(b)) deep
// (the vertex normals only shorten the projection), so the relief lies inward of the sheet;
// the texel of padding covers the sideways lean of the sheet's point off that fibre, which is
// at most depth x (the normals' spread over a sub-triangle). Vertices are shared wherever base
// triangles share an edge (truth/base_prisms.h), so the sheet has no cracks,
// and all of it is pushed outward by a rounding margin.
//
// n only decides how thick the band between sheet and relief is, so how far the exact walk goes
// (a speed knob), never the answer.
#include <functional>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "truth/base_prisms.h"

namespace rl {

class ShellSheets {
 public:
  // The least depth (map units) of the relief over a uv box [lo, hi], padded by a texel.
  using LeastDepth = std::function<double(const glm::dvec2& lo, const glm::dvec2& hi)>;

  ShellSheets(const BasePrisms& prisms, const LeastDepth& least_depth, double depth,
              double texels_per_sub_edge, size_t max_triangles);
  ~ShellSheets();
  ShellSheets(const ShellSheets&) = delete;
  ShellSheets& operator=(const ShellSheets&) = delete;

  RTCScene scene() const { return scene_; }
  int subdivision() const { return n_; }
  size_t triangles() const { return indices_.size(); }
  // The base triangle under sheet triangle `primitive`.
  unsigned base_triangle(unsigned primitive) const { return primitive / unsigned(n_ * n_); }
  // Is the ray entering the sheet (meeting the triangle from outside)?
  bool entering(unsigned primitive, const glm::dvec3& direction) const;
  // Is world point x (at prism point p) outside the sheet over p by more than the margin: no
  // relief can be met before the ray enters the sheet again?
  bool outside(const glm::dvec3& x, const PrismPoint& p) const;

 private:
  size_t local(int i, int j) const;  // grid vertex (i, j) of one base triangle, i + j <= n
  void number_vertices();
  std::vector<double> least_depths(const LeastDepth& least_depth) const;
  void place_vertices(const std::vector<double>& least, double depth);
  glm::dvec3 outward(const glm::uvec3& tri, const glm::dvec3& normal) const;

  const BasePrisms& prisms_;
  int n_ = 1;
  double margin_ = 0;
  std::vector<unsigned> grid_;  // per base triangle, per local grid vertex: its sheet vertex
  std::vector<glm::vec3> vertices_;
  std::vector<glm::uvec3> indices_;  // n^2 per base triangle, in base-triangle order
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace rl
