#include "run/asset_check.h"

#include <cstdio>
#include <mutex>
#include <set>

#include "core/error.h"
#include "core/hash.h"
#include "relief/image_io.h"
#include "relief/mesh_bake.h"
#include "scene/relief_asset.h"
#include "scene/scene_objects.h"

namespace rl {

namespace {

// What the mesh of `r` must close a solid for ("" when an open mesh is fine: a heightfield bake
// from the top sees only its upper surface).
std::string needs_closed_mesh(const ReliefSourceDesc& r) {
  if (r.cells.active) return "a cubic cell complex classifies cells inside and outside";
  if (r.faces >= 2) return "an object from several heightfields is the intersection of solids";
  if (r.layers > 0) return "a multilayer bake pairs entries and exits";
  return "";
}

// The run log's warning for an open mesh, or "".
std::string closure_warning(const SceneDesc& scene, const TriangleMesh& mesh) {
  const std::string why = needs_closed_mesh(scene.relief);
  if (why.empty()) return "";
  const MeshClosure c = mesh_closure(mesh);
  if (c.closed()) return "";
  return "relieflab: warning: scene " + scene.name + ": mesh " + scene.relief.mesh_path +
         " is not closed (" + std::to_string(c.boundary_edges) + " boundary edge(s), " +
         std::to_string(c.non_manifold_edges) + " non-manifold edge(s)), and " + why +
         ": expect errors where rays pass through its gaps, counted against it";
}

// The image sources that loaded cleanly in this process, by their files' bytes and how they
// are read: configs checked again and again (`verify`, the fuzz tests) decode each once.
std::string image_source_key(const ReliefImageSource& s) {
  std::string key;
  for (const std::string* path : {&s.normal_path, &s.depth_path, &s.color_path})
    key += *path + "=" + (path->empty() ? "" : hex64(file_content_hash(*path))) + "|";
  char options[64];
  std::snprintf(options, sizeof options, "%d%d%d|%.17g", s.height_convention, s.flip_green,
                s.normalize, s.nodata);
  return key + options;
}

void check_relief_images(const ReliefImageSource& source) {
  static std::mutex mutex;
  static std::set<std::string> clean;
  const std::string key = image_source_key(source);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (clean.count(key)) return;
  }
  load_relief_images(source, 1.0);
  const std::lock_guard<std::mutex> lock(mutex);
  clean.insert(key);
}

}  // namespace

std::vector<std::string> check_sweep_assets(const SweepConfig& config) {
  std::vector<std::string> warnings;
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
      if (!r.normal_path.empty() || !r.depth_path.empty()) check_relief_images(image_source(r));
      if (r.normal_path.empty() && !r.depth_path.empty())
        if (const std::string why = depth_file_alpha_problem(r.depth_path); !why.empty())
          warnings.push_back("relieflab: warning: " + at(true, "relief") + why);
      if (!r.mesh_path.empty())
        if (std::string w = closure_warning(scene, load_mesh(r.mesh_path)); !w.empty())
          warnings.push_back(std::move(w));
      where = at(true, "meta_relief");
      for (const MetaLayerDesc& layer : scene.meta.layers)
        if (!layer.relief.normal_path.empty() || !layer.relief.depth_path.empty())
          check_relief_images(image_source(layer.relief));
      where = at(false, "base");
      if (scene.base.kind == "file") load_mesh(scene.base.path);
      where = at(false, "objects");
      if (!scene.objects.empty()) make_object_mesh(scene.objects);
    } catch (const ConfigError& e) {
      throw ConfigError(where + e.what());
    }
  }
  return warnings;
}

}  // namespace rl
