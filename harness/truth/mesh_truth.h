#pragma once
// The "source" truth of a baked relief: the original mesh (or a procedural pattern mesh),
// mapped into the bake's texture space and traced by Embree. Against it a technique's error
// includes the representation error of the heightfield (overhangs, resolution, quantisation), not
// only its search error.
#include <vector>

#include <embree3/rtcore.h>

#include "relief/mesh_bake.h"
#include "truth/truth_surface.h"

namespace rl {

class MeshTruth final : public TruthSurface {
 public:
  // `tiled`: the mesh is one tile of a periodic pattern with its neighbours
  // (relief/pattern_mesh.h with_neighbour_tiles) and rays walk
  // the tiles they cross, as the heightfield truth does.
  MeshTruth(const TriangleMesh& mesh, const BakeFrame& frame,
            const ReverseProjection& projection = {}, bool tiled = false);
  ~MeshTruth() override;
  MeshTruth(const MeshTruth&) = delete;
  MeshTruth& operator=(const MeshTruth&) = delete;

  TruthHit intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                     double t_max) const override;
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                double t_max) const override;
  float max_depth() const override { return 1.0f; }
  double tessellation_bound() const override { return 0.0; }  // the mesh is the surface
  double build_ms() const override { return build_ms_; }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  double build_ms_ = 0;
  std::vector<glm::dvec3> affine_normals_;  // per triangle, in the bake box's affine space
  std::vector<glm::vec3> colors_;           // per triangle, or empty
  bool tiled_ = false;
};

}  // namespace rl
