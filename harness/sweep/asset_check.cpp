#include "sweep/asset_check.h"

#include "core/error.h"
#include "relief/image_io.h"
#include "relief/mesh_bake.h"
#include "scene/relief_asset.h"
#include "scene/scene_objects.h"

namespace rl {

void check_sweep_assets(const SweepConfig& config) {
  for (const SceneDesc& scene : config.scenes) {
    const std::string where = config.source + ": scene '" + scene.name + "': ";
    try {
      const ReliefSourceDesc& r = scene.relief;
      if (!r.normal_path.empty() || !r.depth_path.empty()) load_relief_images(image_source(r), 1.0);
      if (!r.mesh_path.empty()) load_mesh(r.mesh_path);
      if (scene.base.kind == "file") load_mesh(scene.base.path);
      if (!scene.objects.empty()) make_object_mesh(scene.objects);
    } catch (const ConfigError& e) {
      throw ConfigError(where + e.what());
    }
  }
}

}  // namespace rl
