#pragma once
// meta_relief = { ... } of a [[scene]] (Limberger, Schetinger & Oliveira, Section III): finer
// relief layers on top of the scene's relief, with their tilings and weights, combined at run
// time or baked. Parsing only; image sizes come from read_scene_files().
#include <string>

#include <nlohmann/json.hpp>

#include "config/config_toml.h"
#include "scene/scene.h"

namespace rl {

// Reads `meta_relief` of scene table `t` into s.meta and checks that the scene can have it
// (heightfield layers on a base drawn itself). Enters it into `canon` only when present, so
// other scenes keep their keys. Call after the effects are known.
void parse_meta_relief(const toml::table& t, const Src& src, const std::string& base_dir,
                       const toml::node& scene_node, SceneDesc& s, nlohmann::json& canon);

}  // namespace rl
