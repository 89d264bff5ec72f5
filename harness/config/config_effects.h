#pragma once
// The options of a [[scene]]'s effects: ambient_occlusion = { ... } (Limberger et al.,
// Section IV) and shadow_map = { ... } (scene_shadows). Parsing only.
#include <nlohmann/json.hpp>

#include "config/config_toml.h"
#include "scene/scene.h"

namespace rl {

// Reads `ambient_occlusion` of scene table `t` into s.ao and checks that the scene can have
// the effect (a heightfield on the plane or a curved base, drawn on its base). Enters the
// options into `canon` only when the scene asks for the effect, so other scenes keep their keys.
void parse_effect_options(const toml::table& t, const Src& src, const toml::node& scene_node,
                          SceneDesc& s, nlohmann::json& canon);

// Reads `shadow_map` = { size, depth, bias, slope_bias } of scene table `t` into s.shadow_map and
// checks that the scene can have scene_shadows: a heightfield or multilayer relief drawn on its
// base (planar or curved), in the plain projection, lit from outside its bounds (objects included:
// read after them) and, on the planar base, from above. Enters the options into `canon` only when
// the scene asks for the effect.
void parse_scene_shadows(const toml::table& t, const Src& src, const toml::node& scene_node,
                         SceneDesc& s, nlohmann::json& canon);

}  // namespace rl
