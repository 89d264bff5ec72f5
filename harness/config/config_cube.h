#pragma once
// The scene settings of an object drawn in its bounding cube: a cell complex (relief = { cells
// = ... }) or an object from several heightfields (relief = { mesh = ..., faces = N }).
#include "config/config_toml.h"
#include "scene/scene.h"

namespace rl {

// Such a scene's fixed settings: drawn in its cube (proxy box, empty floor, fit framing),
// measured against the mesh (a cell complex also against its encoded surface). Fails on keys
// that cannot apply. Does nothing for other scenes.
void apply_in_cube_scene(const toml::table& t, const Src& src, const toml::node& node,
                         SceneDesc& s);

}  // namespace rl
