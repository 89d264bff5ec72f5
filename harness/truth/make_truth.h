#pragma once
// The truth a scene asks for: its map's bilinear heightfield, the mesh it was baked from, or
// its curved base displaced by the map; plus the scene's objects.
#include <memory>

#include "relief/relief_map.h"
#include "scene/scene.h"
#include "truth/displaced_truth.h"
#include "truth/objects_truth.h"
#include "truth/pattern_base_truth.h"
#include "truth/truth_render.h"
#include "truth/truth_surface.h"

namespace rl {

// The texture-space truth of a relief on the planar base.
std::unique_ptr<TruthSurface> make_truth(const SceneDesc& scene, const ReliefMap& map,
                                         double tolerance);

// Everything the truth of one (scene, texture resolution) traces: the relief -- a texture-space
// surface on the planar base, or the displaced curved base -- and the scene's plain objects,
// nearest hit per pixel.
class SceneTruth {
 public:
  // `base`: the scene's curved base mesh if already built (else built here).
  SceneTruth(const SceneDesc& scene, const ReliefMap& map, double tolerance,
             const BaseMesh* base = nullptr);
  ~SceneTruth();
  GBuffer render(const ReliefMap& map, const SceneDesc& scene, const Camera& camera,
                 EffectSet effects, TruthStats* stats = nullptr,
                 AoTruthCache* ao_cache = nullptr) const;
  double tessellation_bound() const;  // depth units
  int subdivision() const;
  double build_ms() const { return build_ms_; }

 private:
  std::unique_ptr<TruthSurface> planar_;
  std::unique_ptr<DisplacedTruth> displaced_;
  std::unique_ptr<PatternBaseTruth> pattern_;  // a pattern on a curved base
  std::unique_ptr<ObjectsTruth> objects_;
  double build_ms_ = 0;
};

}  // namespace rl
