#include "technique/technique.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <stdexcept>

#include "core/columns.h"
#include "core/error.h"

namespace rl {

void render_frame(Technique& technique, const FrameInput& frame, RenderTarget::Kind target) {
  render_shadow_map(technique, frame);
  render_scene(technique, frame, target);
}

void render_shadow_map(Technique& technique, const FrameInput& frame) {
  if (frame.shadow_map) frame.shadow_map->render(technique, frame);
}

void render_scene(Technique& technique, const FrameInput& frame, RenderTarget::Kind target) {
  if (frame.objects) frame.objects->draw(frame.scene, frame.camera, target, frame.shadow_map);
  technique.render(frame, target);
}

namespace {

bool is_identifier(const std::string& s) {
  if (s.empty() || !std::islower(static_cast<unsigned char>(s[0]))) return false;
  for (char c : s)
    if (!(std::islower(static_cast<unsigned char>(c)) ||
          std::isdigit(static_cast<unsigned char>(c)) || c == '_'))
      return false;
  return true;
}

// The path from the repository's techniques/ (or harness/) folder on, for messages.
std::string short_source(const std::string& path) {
  for (const char* root : {"techniques/", "harness/", "tests/"}) {
    const size_t at = path.rfind(root);
    if (at != std::string::npos) return path.substr(at);
  }
  return path;
}

}  // namespace

// Texts printed in one Markdown table cell and one report line: a line break or another
// control character would end the table or forge the lines after it.
void require_one_line(const std::string& text, const std::string& what) {
  for (char c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      throw std::logic_error(what + " must be one line without control characters");
}

void check_technique_info(const TechniqueInfo& info) {
  const std::string who = "technique '" + info.name + "'";
  if (!is_identifier(info.name))
    throw std::logic_error(who + ": a name is lower-case letters, digits and '_'");
  require_one_line(info.title, who + ": its title");
  require_one_line(info.citation, who + ": its citation");
  std::set<std::string> seen;
  for (const ParamSpec& p : info.params) {
    const std::string param = who + " parameter '" + p.name + "'";
    if (!is_identifier(p.name))
      throw std::logic_error(param + ": a name is lower-case letters, digits and '_'");
    if (!seen.insert(p.name).second) throw std::logic_error(param + " is declared twice");
    if (!(p.min_value <= p.max_value))
      throw std::logic_error(param + ": min " + std::to_string(p.min_value) + " > max " +
                             std::to_string(p.max_value));
    if (!(p.default_value >= p.min_value && p.default_value <= p.max_value))
      throw std::logic_error(param + ": default " + std::to_string(p.default_value) + " outside [" +
                             std::to_string(p.min_value) + ", " + std::to_string(p.max_value) +
                             "]");
    if (p.kind != ParamKind::Float && p.default_value != std::floor(p.default_value))
      throw std::logic_error(param + ": an " + param_kind_name(p.kind) +
                             " default must be a whole number");
    if (p.kind == ParamKind::Bool && (p.min_value != 0 || p.max_value != 1))
      throw std::logic_error(param + ": a bool ranges over [0, 1]");
    if (p.doc.empty()) throw std::logic_error(param + " needs a doc string");
    require_one_line(p.doc, param + ": its doc string");
  }
  check_contract(info.name, info.contract, info.params);
}

TechniqueRegistry& TechniqueRegistry::instance() {
  static TechniqueRegistry registry;
  return registry;
}

// A parameter is a rows.csv column of its own: one named like a result column (or a column
// named like another technique's parameter) would make two columns of one name in every row.
void TechniqueRegistry::refuse_parameters_named_like_columns(const TechniqueEntry& entry) const {
  const std::string& name = entry.info.name;
  for (const ParamSpec& p : entry.info.params)
    if (const DeclaredColumn* c = find_column(p.name))
      throw std::logic_error("technique '" + name + "' parameter '" + p.name +
                             "' is named like the rows.csv column '" + c->spec.name + "' that " +
                             c->producer + " writes: rename the parameter");
  for (const ColumnSpec& c : entry.info.columns)
    for (const auto& [other_name, other] : entries_)
      for (const ParamSpec& q : other.info.params)
        if (q.name == c.name)
          throw std::logic_error("technique '" + name + "' declares a column '" + c.name +
                                 "' named like technique '" + other_name +
                                 "''s parameter: rename the column");
}

void TechniqueRegistry::add(TechniqueEntry entry) {
  check_technique_info(entry.info);
  const std::string& name = entry.info.name;
  if (const TechniqueEntry* other = find(name))
    throw std::logic_error("technique '" + name + "' is registered twice: by " +
                           short_source(other->source) + " and by " + short_source(entry.source));
  for (const ParamSpec& p : entry.info.params)
    for (const auto& [other_name, other] : entries_)
      for (const ParamSpec& q : other.info.params)
        if (q.name == p.name && q.kind != p.kind)
          throw std::logic_error(
              "technique '" + name + "' parameter '" + p.name + "' (" + param_kind_name(p.kind) +
              ") shares its name, and so its rows.csv column, with technique '" + other_name +
              "''s " + param_kind_name(q.kind) + " parameter: one name, one quantity");
  refuse_parameters_named_like_columns(entry);
  declare_columns("technique " + name, entry.info.columns);  // throws on a unit conflict
  entries_.emplace(name, std::move(entry));
}

namespace {
std::string* registration_error_sink = nullptr;
}  // namespace

void set_registration_error_sink(std::string* sink) {
  registration_error_sink = sink;
}

void refuse_registration(const std::string& why) {
  if (registration_error_sink) {
    *registration_error_sink += std::string(registration_error_sink->empty() ? "" : "; ") + why;
    return;
  }
  std::fprintf(stderr, "relieflab: plugin registration failed: %s\n", why.c_str());
  std::exit(3);
}

void register_or_exit(TechniqueEntry entry) {
  try {
    TechniqueRegistry::instance().add(std::move(entry));
  } catch (const std::logic_error& e) {
    refuse_registration(e.what());
  }
}

void TechniqueRegistry::remove(const std::string& name) {
  entries_.erase(name);
}

void TechniqueRegistry::set_plugin(const std::string& name, const std::string& path) {
  auto it = entries_.find(name);
  if (it != entries_.end()) it->second.plugin = path;
}

const TechniqueEntry* TechniqueRegistry::find(const std::string& name) const {
  auto it = entries_.find(name);
  return it == entries_.end() ? nullptr : &it->second;
}

std::vector<std::string> TechniqueRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& [name, e] : entries_) out.push_back(name);
  return out;
}

ParamValues TechniqueRegistry::resolve(const std::string& name, const ParamValues& params,
                                       const std::string& where) const {
  const TechniqueEntry* e = find(name);
  if (!e) {
    std::string known;
    for (const auto& n : names()) known += (known.empty() ? "" : ", ") + n;
    throw ConfigError(where + ": unknown technique '" + name + "' (known: " + known + ")");
  }
  ParamValues resolved = resolve_params(e->info.params, params, where);
  if (e->validate) e->validate(resolved, where + ": technique '" + name + "'");
  return resolved;
}

std::unique_ptr<Technique> TechniqueRegistry::create(const std::string& name,
                                                     const ParamValues& params,
                                                     const std::string& where) const {
  ParamValues resolved = resolve(name, params, where);  // throws for unknown names
  return find(name)->create(resolved);
}

std::string cannot_render(const TechniqueInfo& info, const SceneDesc& s) {
  if (!info.effects.contains_all(s.drawn_effects()))
    return "it does not support effect(s) " +
           join_effects(info.effects.missing_from(s.drawn_effects())) +
           " (it supports: " + join_effects(info.effects) + "); drop the effect";
  return cannot_draw(info.draws, s);
}

}  // namespace rl
