#pragma once
// relief = { cells = "mesh.obj", grid = 4 | "auto", resolution = 64, ... } of a [[scene]]: a
// closed mesh encoded as a cubic cell complex (Apaza & Andujar; relief/cell_complex.h), and
// config_cube.h has the scene settings that follow from it (its bounding cube is the box proxy).
#include <string>

#include <nlohmann/json.hpp>

#include "config/config_toml.h"
#include "scene/scene.h"

namespace rl {

// Parses a relief table that has 'cells' into `r` (mesh_path, up, native size, cells options).
void parse_cells_relief(const toml::table& t, const Src& src, const std::string& base_dir,
                        ReliefSourceDesc& r, nlohmann::json& canon);

}  // namespace rl
