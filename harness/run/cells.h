#pragma once
// Sweep expansion: the product of scenes x techniques x parameter settings x texture
// resolutions x viewports x views, each cell keyed by a stable hash of what the config varies
// (the code and the inputs' roles are in each row's provenance beside it:
// run/cell_provenance.h). Cells sharing (scene, texture resolution, viewport, view) share one
// truth.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/config.h"
#include "core/params.h"

namespace rl {

struct Cell {
  size_t scene_index = 0;
  std::string technique;
  ParamValues params;   // every declared parameter (defaults filled in)
  int texture_res = 0;  // resolved (never 0)
  int width = 0, height = 0;
  View view;
  std::string key;        // result-store key
  std::string asset_key;  // (scene, texture_res): relief map, GPU textures, Embree scene
  std::string truth_key;  // (scene, texture_res, viewport, view): one truth G-buffer
  // Identity columns of the row: technique, scene, view, sizes, parameters.
  nlohmann::ordered_json identity;
};

// Every cell of the sweep, once: a cell whose key an earlier one already has (a repeated
// elevation or view, a [[technique]] block given twice) is dropped and counted in
// `duplicates`.
std::vector<Cell> expand_cells(const SweepConfig& config, size_t* duplicates = nullptr);
// Every parameter column of the sweep, in order of first appearance.
std::vector<std::string> parameter_columns(const SweepConfig& config);

}  // namespace rl
