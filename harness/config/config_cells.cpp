#include "config/config_cells.h"

#include "relief/cell_complex.h"

namespace rl {

void parse_cells_relief(const toml::table& t, const Src& src, const std::string& base_dir,
                        ReliefSourceDesc& r, nlohmann::json& canon) {
  check_keys(t,
             {"cells", "grid", "resolution", "up", "threshold", "grid_max", "distance_bits",
              "subdivide", "sampling"},
             src, "a cell-complex relief");
  const toml::node& mn = *t.get("cells");
  r.mesh_path = resolve_path(string_of(mn, src, "cells"), base_dir, src, mn);
  r.cells.active = true;
  if (auto* n = t.get("up")) {
    const std::string up = string_of(*n, src, "up");
    if (up != "x" && up != "y" && up != "z") fail(src.at(*n), "'up' must be \"x\", \"y\" or \"z\"");
    r.mesh_up = up[0] - 'x';
  }
  if (auto* n = t.get("grid")) {
    if (n->is_string()) {
      if (string_of(*n, src, "grid") != "auto")
        fail(src.at(*n), "'grid' must be a cell count per side (1 to " +
                             std::to_string(kMaxCellGrid) + ") or \"auto\"");
      r.cells.grid = 0;
    } else {
      r.cells.grid = positive_int(*n, src, "grid", 1, kMaxCellGrid);
    }
  }
  const int res =
      t.get("resolution") ? positive_int(*t.get("resolution"), src, "resolution", 2, 1024) : 64;
  r.native = {res, res};
  if (auto* n = t.get("threshold")) r.cells.threshold = number_in(*n, src, "threshold", 0, 1);
  if (auto* n = t.get("grid_max"))
    r.cells.grid_max = positive_int(*n, src, "grid_max", 1, kMaxCellGrid);
  if (r.cells.grid > 0 && (t.contains("threshold") || t.contains("grid_max")))
    fail(src.at(t),
         "'threshold' and 'grid_max' choose the grid when grid = \"auto\"; this "
         "relief sets grid = " +
             std::to_string(r.cells.grid));
  if (auto* n = t.get("distance_bits")) {
    r.cells.distance_bits = positive_int(*n, src, "distance_bits", 8, 16);
    if (r.cells.distance_bits != 8 && r.cells.distance_bits != 16)
      fail(src.at(*n), "'distance_bits' must be 16 (Table 1) or 8");
  }
  if (auto* n = t.get("subdivide")) r.cells.subdivide = positive_int(*n, src, "subdivide", 0, 4);
  if (auto* n = t.get("sampling")) {
    const std::string s = string_of(*n, src, "sampling");
    if (s != "cpu" && s != "gpu")
      fail(src.at(*n),
           "'sampling' must be \"cpu\" (each texel's projection line traced) or "
           "\"gpu\" (the maps drawn through a geometry shader, Section 3.3.2), got \"" +
               s + "\"");
    r.cells.gpu_sampling = s == "gpu";
  }
  canon["cells"] = true;
  canon["subdivide"] = r.cells.subdivide;
  canon["up"] = r.mesh_up;
  canon["grid"] = r.cells.grid;
  canon["resolution"] = res;
  canon["distance_bits"] = r.cells.distance_bits;
  if (r.cells.gpu_sampling) canon["sampling"] = "gpu";  // named only when set: keys stay
  if (r.cells.grid == 0) {
    canon["threshold"] = r.cells.threshold;
    canon["grid_max"] = r.cells.grid_max;
  }
}

}  // namespace rl
