#pragma once
// relief = { ... } of a [[scene]]: a procedural heightfield, a non-height-field pattern
// (weave, helix) baked into depth layers, image files, or a mesh baked into a heightfield or
// into layers. Parsing only; image sizes and mesh proportions come from read_scene_files().
#include <string>

#include <nlohmann/json.hpp>

#include "config/config_toml.h"
#include "scene/scene.h"

namespace rl {

// The relief source, with its canonical description (what keys its cells) in `canon`.
ReliefSourceDesc parse_relief(const toml::node& node, const Src& src, const std::string& base_dir,
                              nlohmann::json& canon);

}  // namespace rl
