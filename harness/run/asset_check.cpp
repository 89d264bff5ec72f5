#include "run/asset_check.h"

#include "core/error.h"
#include "relief/image_io.h"
#include "relief/mesh_bake.h"
#include "scene/relief_asset.h"
#include "scene/scene_objects.h"

namespace rl {

void check_sweep_assets(const SweepConfig& config) {
  for (const SceneDesc& scene : config.scenes) {
    // Where the config asked for the asset: "file:line: scene 'name', key: ".
    auto sites = config.scene_sites.find(scene.name);
    const bool known = sites != config.scene_sites.end();
    auto at = [&](bool relief, const char* key) {
      const std::string line =
          known ? (relief ? sites->second.second : sites->second.first) : config.source;
      return line + ": scene '" + scene.name + "', " + key + ": ";
    };
    std::string where = at(true, "relief");
    try {
      const ReliefSourceDesc& r = scene.relief;
      if (!r.normal_path.empty() || !r.depth_path.empty()) load_relief_images(image_source(r), 1.0);
      if (!r.mesh_path.empty()) load_mesh(r.mesh_path);
      where = at(true, "meta_relief");
      for (const MetaLayerDesc& layer : scene.meta.layers)
        if (!layer.relief.normal_path.empty() || !layer.relief.depth_path.empty())
          load_relief_images(image_source(layer.relief), 1.0);
      where = at(false, "base");
      if (scene.base.kind == "file") load_mesh(scene.base.path);
      where = at(false, "objects");
      if (!scene.objects.empty()) make_object_mesh(scene.objects);
    } catch (const ConfigError& e) {
      throw ConfigError(where + e.what());
    }
  }
}

}  // namespace rl
