#include "technique/contract.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "relief/cell_complex.h"
#include "relief/heightfield_faces.h"
#include "relief/relief_map.h"

namespace rl {

std::string answer_name(Answer a) {
  switch (a) {
    case Answer::Exact:
      return "exact";
    case Answer::Converging:
      return "converging";
    case Answer::Approximation:
      return "approximation";
    case Answer::ShadingOnly:
      return "shading only";
  }
  return "?";
}

RayQuery whole_frame_query(const ParamValues& params, const ReliefMap& map) {
  RayQuery q{.params = params, .map_width = map.width, .map_height = map.height};
  q.layer_groups = std::max(1, (map.layers.count + 3) / 4);
  if (map.faces) q.faces = map.faces->count();
  if (map.cells) q.grid_cells = map.cells->grid();
  q.span_texels = glm::dvec2(map.width, map.height) * 1e3;
  return q;
}

double walk_cells(const RayQuery& q) {
  return std::min(kWalkCellCap, std::floor(q.span_texels.x) + std::floor(q.span_texels.y) + 3);
}

double quadtree_nodes(const RayQuery& q) {
  // Level l's nodes are 2^l cells wide: the ray crosses at most span / 2^l + 2 of them per
  // axis. Summed over the levels: under twice the cells plus two per level and axis.
  const int side = std::max(q.map_width, q.map_height);
  const int levels = 1 + int(std::ceil(std::log2(std::max(side, 1))));
  const double cells = std::floor(q.span_texels.x) + std::floor(q.span_texels.y);
  return std::min(4 * kWalkCellCap, 2 * cells + 4.0 * levels + 3);
}

double linear_binary_t_error(const RayQuery& q) {
  return std::ldexp(one_linear_step(q), -int(q.param("binary_steps")));
}

double one_linear_step(const RayQuery& q) {
  return 1.0 / q.param("linear_steps");
}

double linear_binary_fetches_shaded(const RayQuery& q) {
  return q.param("linear_steps") + q.param("binary_steps") + 2;
}

std::vector<AccuracyKnob> linear_binary_knobs() {
  return {{"linear_steps"}, {"binary_steps"}};
}

ParamValues linear_binary_finest() {
  return {{"linear_steps", 1024}, {"binary_steps", 16}};
}

ParamSpec linear_steps_param(int default_steps, const std::string& doc) {
  return {.name = "linear_steps",
          .kind = ParamKind::Int,
          .default_value = double(default_steps),
          .min_value = 1,
          .max_value = 4096,
          .doc = doc,
          .define = "RL_LINEAR_STEPS"};
}

ParamSpec binary_steps_param(int default_steps, const std::string& doc) {
  return {.name = "binary_steps",
          .kind = ParamKind::Int,
          .default_value = double(default_steps),
          .min_value = 0,
          .max_value = 32,
          .doc = doc,
          .define = "RL_BINARY_STEPS"};
}

void check_contract(const std::string& technique, const TechniqueContract& c,
                    const std::vector<ParamSpec>& params) {
  const std::string who = "technique '" + technique + "' contract";
  if (!c.max_fetches || c.max_fetches_formula.empty())
    throw std::logic_error(who + ": declare max_fetches and its formula in words");
  auto spec = [&](const std::string& name) -> const ParamSpec* {
    for (const ParamSpec& p : params)
      if (p.name == name) return &p;
    return nullptr;
  };
  std::set<std::string> knobs;
  for (const AccuracyKnob& k : c.knobs) {
    if (!spec(k.param))
      throw std::logic_error(who + ": knob '" + k.param + "' is not a declared parameter");
    if (!knobs.insert(k.param).second)
      throw std::logic_error(who + ": knob '" + k.param + "' is declared twice");
  }
  for (const auto& [name, value] : c.finest) {
    const ParamSpec* p = spec(name);
    if (!p || !knobs.count(name))
      throw std::logic_error(who + ": finest setting names '" + name + "', not a knob");
    if (value < p->min_value || value > p->max_value)
      throw std::logic_error(who + ": finest " + name + " = " + std::to_string(value) +
                             " is outside its range");
  }
  if (c.answer == Answer::Converging) {
    if (knobs.empty()) throw std::logic_error(who + ": a converging answer names its knobs");
    for (const std::string& k : knobs)
      if (!c.finest.count(k))
        throw std::logic_error(who + ": a converging answer gives knob '" + k + "' a finest value");
  }
  if (c.t_error && c.accuracy.empty())
    throw std::logic_error(who + ": a stated accuracy says its conditions in words");
}

}  // namespace rl
