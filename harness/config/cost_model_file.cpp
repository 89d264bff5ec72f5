#include "config/cost_model_file.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <set>

#include "config/config_toml.h"
#include "core/data_paths.h"
#include "core/error.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

// Where a model named by `value` lives.
std::string model_path(const std::string& value, const std::string& base_dir,
                       const std::string& where) {
  if (value.size() > 5 && value.substr(value.size() - 5) == ".toml") {
    const fs::path p(value);
    return p.is_absolute() ? value : (fs::path(base_dir) / p).string();
  }
  for (char c : value)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.')
      throw ConfigError(where + ": cost_model '" + value +
                        "' is neither a model's name (letters, digits, '-', '_', '.') nor a "
                        ".toml file");
  return data_root() + "/configs/gpu-models/" + value + ".toml";
}

CostModel parse_model(const std::string& path) {
  const toml::table root = parse_toml_file(path);
  const Src src{path};
  check_keys(root, {"gpu", "weights", "fitted_to", "date", "note"}, src, "the cost model");
  CostModel m;
  m.name = fs::path(path).stem().string();
  const toml::node* gpu = root.get("gpu");
  if (!gpu) throw ConfigError(path + ": the cost model names no 'gpu'");
  m.gpu = string_of(*gpu, src, "gpu");
  const toml::table* weights = root.get("weights") ? root.get("weights")->as_table() : nullptr;
  if (!weights) throw ConfigError(path + ": the cost model has no [weights] table");
  const std::vector<std::string> names = cost_model_weight_names();
  check_keys(*weights, std::set<std::string>(names.begin(), names.end()), src, "[weights]");
  std::vector<double*> slots = {&m.frame_ms, &m.pixel_ms, &m.fragment_ms};
  for (double& op : m.op_ms) slots.push_back(&op);
  for (size_t i = 0; i < names.size(); ++i) {
    const toml::node* w = weights->get(names[i]);
    if (!w) throw ConfigError(path + ": [weights] lacks '" + names[i] + "'");
    // Non-negative: no count makes a frame faster; a fit that says otherwise is not a model.
    *slots[i] = number_in(*w, src, names[i], 0, 1e6);
  }
  // Every weight 0 predicts every frame free: no fit gives that, and every Pareto front in time
  // would collapse to one point.
  if (std::all_of(slots.begin(), slots.end(), [](const double* w) { return *w == 0; }))
    throw ConfigError(path +
                      ": every weight in [weights] is 0, which prices every frame at 0 ms; "
                      "not a fitted model");
  return m;
}

}  // namespace

std::optional<CostModel> load_cost_model(const std::string& value, const std::string& base_dir,
                                         const std::string& where) {
  if (value == "none") return std::nullopt;
  const std::string path = model_path(value, base_dir, where);
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw ConfigError(where + ": cost_model '" + value + "': no model file " + path);
  // A FIFO would block the read, a device or a folder is no model: said as they are.
  if (!fs::is_regular_file(path, ec))
    throw ConfigError(where + ": cost_model '" + value + "': " + path + " is not a regular file");
  try {
    return parse_model(path);
  } catch (const ConfigError& e) {
    throw ConfigError(where + ": cost_model '" + value + "': " + e.what());
  }
}

}  // namespace rl
