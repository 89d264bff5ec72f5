#pragma once
// What the study programs beside the benchmarks share: their command lines' lists, and the cell
// complexes of Apaza & Andujar's Table 1 as apaza-table1 builds them.
#include <sstream>
#include <string>
#include <vector>

#include "config/config.h"

namespace rl::bench {

// "a,b,c" -> {"a", "b", "c"}.
inline std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

// A sweep of one scene: `mesh` (bunny, teapot or dragon) as a cell complex with its grid chosen
// by the occluded-fragment rule and 64^2 maps, drawn by cell_complex. `program` names the
// config in error messages. Needs RELIEFLAB_SOURCE_DIR.
inline SweepConfig table1_mesh_config(const std::string& mesh, const std::string& program) {
  const std::string file = mesh == "dragon" ? "dragon_res3.ply" : mesh + ".obj";
  const std::string toml = "[sweep]\nname = \"" + program +
                           "\"\nelevations = [30]\nviewports = [64]\n[[scene]]\nname = \"" + mesh +
                           "\"\nrelief = { cells = \"assets/meshes/" + file +
                           "\", up = \"y\", grid = \"auto\", resolution = 64 }\n"
                           "[[technique]]\nname = \"cell_complex\"\n";
  return parse_sweep_config(toml, program, RELIEFLAB_SOURCE_DIR);
}

}  // namespace rl::bench
