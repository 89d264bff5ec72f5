#pragma once
// GPU cost models as files (core/cost_model.h): configs/gpu-models/<name>.toml holds a GPU's
// fitted weights; a sweep names one with `[sweep] cost_model`.
#include <optional>
#include <string>

#include "core/cost_model.h"

namespace rl {

// The model a config gives by name ("nvidia-h200": configs/gpu-models/nvidia-h200.toml under
// the data root) or by path (a ".toml" file, relative to the config's folder); "none" gives no
// model. Throws ConfigError naming `where`, the file, the key or the value at fault.
std::optional<CostModel> load_cost_model(const std::string& value, const std::string& base_dir,
                                         const std::string& where);

// The model every sweep uses unless its config names another.
inline constexpr const char* kDefaultCostModel = "nvidia-h200";

}  // namespace rl
