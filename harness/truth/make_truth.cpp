#include "truth/make_truth.h"

#include "relief/mesh_bake.h"
#include "truth/heightfield_truth.h"
#include "truth/mesh_truth.h"

namespace rl {

std::unique_ptr<TruthSurface> make_truth(const SceneDesc& scene, const ReliefMap& map,
                                         double tolerance) {
  if (scene.truth == TruthLevel::Mesh) {
    const TriangleMesh mesh = load_mesh(scene.relief.mesh_path);
    return std::make_unique<MeshTruth>(mesh, bake_frame(mesh, scene.relief.mesh_up),
                                       scene.projection);
  }
  return std::make_unique<HeightfieldTruth>(map, tolerance);
}

}  // namespace rl
