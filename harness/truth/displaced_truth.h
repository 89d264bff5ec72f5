#pragma once
// Truth for a relief on a curved base (DESIGN.md: "a heightfield on a curved base"; chapter
// 5's silhouettes approximate it): the base tessellated finer than the texels, each vertex
// displaced inward along the base normal by depth * d(u, v) (bilinear, as the shaders sample
// it), traced by Embree in world space.
//
// The surface is the base mesh as drawn (its flat triangles, normals interpolated), so the
// technique and the truth share the base and the error is the relief's. Generated bases
// (charts) are sampled on a uv grid whose lines are every texel-centre crease (k per texel)
// and every segment edge: within a cell the displacement is one bilinear patch on one base
// quad, and the two triangles of a cell deviate from the displaced surface by the map's
// twist / (4 k^2) plus the bend of the interpolated normal. Mesh bases (teapot, files) split
// each triangle uniformly n x n. Either way the deviation is measured at every cell centre
// (centroid) and k or n doubled until it meets the tolerance or the triangle budget; the
// achieved figure is reported as the bound.
#include <atomic>
#include <cstdint>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "core/sharded_counter.h"
#include "relief/relief_map.h"
#include "scene/base_mesh.h"
#include "truth/truth_surface.h"

namespace rl {

struct DisplacedHit {
  bool hit = false;
  double t = 0;         // world distance along the (unit) ray
  glm::dvec3 position;  // world
  glm::dvec2 uv;
  glm::dvec3 tangent, bitangent, normal;  // the base's unit frame at the hit (shading)
  // The traced surface's own unit normal there (the hit triangle's, facing the ray): what a
  // vertical error of the truth moves the hit along (truth_hit_bound).
  glm::dvec3 geometric_normal{0, 0, 1};
  // The surface's own shading normal (world, facing the ray) and colour, where the truth has
  // them (a pattern mesh on the base); otherwise the map's at `uv` in the frame above.
  bool has_surface = false;
  glm::dvec3 surface_normal{0}, albedo{0};
};

class DisplacedTruth {
 public:
  // `depth`: world depth of depth 1; `tolerance` in depth units.
  DisplacedTruth(const BaseMesh& base, const ReliefMap& map, double depth, double tolerance,
                 size_t max_triangles = size_t(1) << 22);
  ~DisplacedTruth();
  DisplacedTruth(const DisplacedTruth&) = delete;
  DisplacedTruth& operator=(const DisplacedTruth&) = delete;

  DisplacedHit intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_max) const;
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                double t_max) const;

  double tessellation_bound() const { return bound_; }  // depth units, measured
  // As TruthSurface's: the deviation along the base's normal, and Embree's float rounding.
  double vertical_bound() const { return bound_; }
  double rounding_bound() const { return TruthSurface::kEmbreeRounding; }
  int subdivision() const { return subdivision_; }  // k per texel, or n per base triangle
  size_t triangles() const { return indices_.size() / 3; }
  double build_ms() const { return build_ms_; }
  uint64_t primary_rays() const { return primary_rays_.load(); }
  uint64_t shadow_rays() const { return shadow_rays_.load(); }

 private:
  struct Vertex {
    glm::vec3 position;
    glm::vec2 uv;
    glm::vec3 tangent, bitangent, normal;
  };
  void build_from_charts(const BaseMesh& base, const ReliefMap& map, double depth, double tolerance,
                         size_t max_triangles);
  double tessellate_chart(const BaseMesh& base, const SurfaceChart& chart, unsigned first_base,
                          const std::vector<double>& u, const std::vector<double>& v,
                          const ReliefMap& map, double depth);
  void build_from_triangles(const BaseMesh& base, const ReliefMap& map, double depth,
                            double tolerance, size_t max_triangles);

  std::vector<Vertex> vertices_;
  std::vector<unsigned> indices_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  int subdivision_ = 1;
  double bound_ = 0;
  double build_ms_ = 0;
  mutable ShardedCounter primary_rays_, shadow_rays_;
};

}  // namespace rl
