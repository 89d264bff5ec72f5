#pragma once
// relief = { cells = "mesh.obj", grid = 4 | "auto", resolution = 64, ... } of a [[scene]]: a
// closed mesh encoded as a cubic cell complex (Apaza & Andujar; relief/cell_complex.h), and
// the scene settings that follow from it (its bounding cube is the box proxy).
#include <string>

#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "sweep/config_toml.h"

namespace rl {

// Parses a relief table that has 'cells' into `r` (mesh_path, up, native size, cells options).
void parse_cells_relief(const toml::table& t, const Src& src, const std::string& base_dir,
                        ReliefSourceDesc& r, nlohmann::json& canon);

// A cell-complex scene's fixed settings: drawn in its cube (proxy box, empty floor), measured
// against the mesh unless it asks for the encoded surface. Fails on keys that cannot apply.
void apply_cells_scene(const toml::table& t, const Src& src, const toml::node& node, SceneDesc& s);

}  // namespace rl
