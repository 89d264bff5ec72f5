#include "truth/make_truth.h"

#include <chrono>
#include <cmath>

#include "core/elapsed.h"
#include "scene/base_mesh.h"
#include "scene/relief_asset.h"

#include "relief/layer_bake.h"
#include "relief/mesh_bake.h"
#include "relief/pattern_mesh.h"
#include "truth/cell_complex_truth.h"
#include "truth/heightfield_truth.h"
#include "truth/layers_truth.h"
#include "truth/mesh_truth.h"
#include "truth/meta_relief_truth.h"
#include "truth/pattern_base_truth.h"

namespace rl {

std::unique_ptr<TruthSurface> make_truth(const SceneDesc& scene, const ReliefMap& map,
                                         double tolerance) {
  if (scene.truth == TruthLevel::Cells) return std::make_unique<CellComplexTruth>(map.cells);
  if (scene.truth == TruthLevel::Layers)
    return std::make_unique<LayersTruth>(map, !scene.impostor());
  if (scene.truth == TruthLevel::Mesh && scene.relief.pattern_mesh()) {
    const TriangleMesh mesh = make_pattern_mesh(scene.relief.procedural, scene.relief.options,
                                                "scene '" + scene.name + "'");
    return std::make_unique<MeshTruth>(with_neighbour_tiles(mesh), pattern_frame(),
                                       ReverseProjection{}, true);
  }
  if (scene.truth == TruthLevel::Mesh) {
    const TriangleMesh mesh = load_mesh(scene.relief.mesh_path);
    return std::make_unique<MeshTruth>(mesh, relief_bake_frame(scene.relief, mesh),
                                       scene.projection);
  }
  // A meta-relief's truth is its layers' combination, whether the technique combines them at
  // run time or samples a bake.
  if (map.meta) return std::make_unique<MetaReliefTruth>(map.meta);
  return std::make_unique<HeightfieldTruth>(map, tolerance);
}

SceneTruth::SceneTruth(const SceneDesc& scene, const ReliefMap& map, double tolerance,
                       const BaseMesh* base) {
  const auto start = std::chrono::steady_clock::now();
  if (scene.base.curved() && scene.relief.layers > 0) {
    std::optional<glm::vec3> floor;
    if (!scene.empty_floor) floor = scene.floor_color;
    pattern_ = std::make_unique<PatternBaseTruth>(
        layered_tile_mesh(scene), base ? *base : make_base_mesh(scene.base, scene.size, scene.tile),
        scene.depth, floor);
  } else if (scene.base.curved()) {
    displaced_ = std::make_unique<DisplacedTruth>(
        base ? *base : make_base_mesh(scene.base, scene.size, scene.tile), map, scene.depth);
  } else {
    planar_ = make_truth(scene, map, tolerance);
  }
  if (!scene.objects.empty()) objects_ = std::make_unique<ObjectsTruth>(scene.objects);
  build_ms_ = ms_since(start);
}

SceneTruth::~SceneTruth() = default;

GBuffer SceneTruth::render(const ReliefMap& map, const SceneDesc& scene, const Camera& camera,
                           EffectSet effects, TruthStats* stats, AoTruthCache* ao_cache) const {
  const ObjectsTruth* objects = objects_.get();
  if (pattern_)
    return render_truth(*pattern_, map, scene, camera, effects, stats, objects, ao_cache);
  if (displaced_)
    return render_truth(*displaced_, map, scene, camera, effects, stats, objects, ao_cache);
  return render_truth(*planar_, map, scene, camera, effects, stats, objects, ao_cache);
}

double SceneTruth::tessellation_bound() const {
  if (pattern_) return pattern_->tessellation_bound();
  return displaced_ ? displaced_->tessellation_bound() : planar_->tessellation_bound();
}

int SceneTruth::subdivision() const {
  if (pattern_) return pattern_->subdivision();
  return displaced_ ? displaced_->subdivision() : planar_->subdivision();
}

}  // namespace rl
