#pragma once
// Procedural relief maps at any resolution, sampled at texel centres. Each generator is a
// hard case of its own: smooth slopes (sines), sharp peaks (pyramids), vertical steps
// (bricks), one-texel-thick walls (walls), and the analytic flat / constant maps.
#include <map>
#include <string>
#include <vector>

#include "relief/relief_map.h"

namespace rl {

struct ProceduralOption {
  std::string name;
  double default_value;
  std::string doc;
  double min_value, max_value;  // accepted range (inclusive)
};

struct ProceduralKind {
  std::string name;
  std::string doc;
  std::vector<ProceduralOption> options;
};

const std::vector<ProceduralKind>& procedural_kinds();

// Builds `kind` at resolution x resolution. `options` may override the kind's option defaults
// (unknown names throw ConfigError naming `where`). Normals are those of the heightfield for
// the given slope scale (world relief depth / world texel width at this resolution).
ReliefMap make_procedural(const std::string& kind, int resolution,
                          const std::map<std::string, double>& options, double depth_per_texel,
                          const std::string& where);

}  // namespace rl
