#pragma once
// Every asset a sweep will read, opened and validated before the first cell runs, so that a
// bad file in a later scene stops the run before anything is written.
#include <string>
#include <vector>

#include "config/config.h"

namespace rl {

// Decodes every relief image in full (a truncated file fails here, not mid-run), checks the
// channels each scene needs, and loads every mesh file (baked reliefs, bases, objects), which
// rejects non-finite and degenerate meshes. Throws ConfigError naming the scene and the file.
// Returns warnings for the run log: a mesh that must close a solid (a cell complex, an object
// from several heightfields, a multilayer bake) but is open or non-manifold, with the counts.
std::vector<std::string> check_sweep_assets(const SweepConfig& config);

}  // namespace rl
