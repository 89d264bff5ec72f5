#pragma once
// Truth of a non-height-field pattern (relief/pattern_mesh.h) on a curved base: for every
// base triangle, the periodic pattern mesh over its uv triangle, clipped to it and mapped by
// its barycentrics onto the base as drawn -- the point at (u, v) on the flat triangle, moved
// inward along the interpolated normal by depth x the scene's depth, as the displaced
// heightfield truth does -- traced by Embree in world space with the pattern's flat triangle
// normals and thread colours. Within a base triangle the mapping is affine, so the pattern's
// triangles stay flat and exact; across base edges the clipped pieces meet without cracks.
// Works on any base with uvs, including mappings that cover some uvs twice (the teapot). With a
// solid floor the tile gains the square at depth 1, placed as the pattern is.
#include <atomic>
#include <cstdint>
#include <optional>
#include <vector>

#include <embree3/rtcore.h>

#include "core/sharded_counter.h"
#include "core/triangle_mesh.h"
#include "scene/base_mesh.h"
#include "truth/displaced_truth.h"

namespace rl {

class PatternBaseTruth {
 public:
  // `depth`: world depth of depth 1. `floor_color`: a solid floor at depth 1 (the underlying
  // model where rays miss the pattern: Policarpo & Oliveira 2006, Figure 9 right), shaded with
  // the base's interpolated normal in that colour; none: rays through the gaps go on.
  PatternBaseTruth(const TriangleMesh& pattern_tile, const BaseMesh& base, double depth,
                   const std::optional<glm::vec3>& floor_color = std::nullopt);
  ~PatternBaseTruth();
  PatternBaseTruth(const PatternBaseTruth&) = delete;
  PatternBaseTruth& operator=(const PatternBaseTruth&) = delete;

  DisplacedHit intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_max) const;
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                double t_max) const;

  double tessellation_bound() const { return 0.0; }
  double vertical_bound() const { return 0.0; }  // the pattern mesh itself, placed exactly
  double rounding_bound() const { return TruthSurface::kEmbreeRounding; }
  int subdivision() const { return 1; }
  size_t triangles() const { return triangles_.size(); }
  double build_ms() const { return build_ms_; }
  uint64_t primary_rays() const { return primary_rays_.load(); }
  uint64_t shadow_rays() const { return shadow_rays_.load(); }

 private:
  struct TileOnTriangle;
  void add_clipped(const TriangleMesh& pattern, uint32_t t, const TileOnTriangle& on);

  std::vector<glm::vec3> positions_;
  std::vector<glm::vec2> uvs_;
  std::vector<glm::vec3> base_normals_;  // the base's normal under each vertex
  std::vector<glm::uvec3> triangles_;
  std::vector<glm::vec3> colors_;
  std::vector<bool> on_floor_;           // per triangle: a piece of the solid floor
  uint32_t first_floor_triangle_ = ~0u;  // in the tile: the floor's triangles come last
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  double build_ms_ = 0;
  mutable ShardedCounter primary_rays_, shadow_rays_;
};

}  // namespace rl
