#pragma once
// [[scene]] tables of a sweep config: relief, base, objects, camera, material, effects and
// framing, checked key by key. Parsing only: no file is read here; what comes from files
// (image sizes, mesh proportions and uvs, content hashes) is filled in by read_scene_files()
// (config/scene_files.h) from the sites recorded here.
#include <string>

#include <nlohmann/json.hpp>

#include "config/config_toml.h"
#include "config/scene_input.h"
#include "scene/scene.h"

namespace rl {

// Where a scene's file-derived facts were asked for, for messages ("file:line").
struct SceneSites {
  std::string scene;   // the [[scene]] table
  std::string relief;  // its relief = { ... }
  std::string base;    // its base = "mesh.obj", when a file
};

struct ParsedScene {
  SceneDesc scene;
  nlohmann::json canon;  // what defines the scene's results (keys cells; see run/cells.h)
  SceneSites sites;
  std::vector<SceneInput> inputs;  // filled by read_scene_files(), in a fixed order
};

ParsedScene parse_scene(const toml::table& t, const Src& src, const std::string& base_dir,
                        const toml::node& node);

}  // namespace rl
