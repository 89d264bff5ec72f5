#include "config/config_technique.h"

#include <algorithm>
#include <set>

#include "technique/technique.h"

namespace rl {
namespace {

const ParamSpec* find_param(const TechniqueInfo& info, const std::string& name) {
  for (const ParamSpec& p : info.params)
    if (p.name == name) return &p;
  return nullptr;
}

[[noreturn]] void unknown_param(const TechniqueInfo& info, const std::string& where,
                                const std::string& key) {
  std::string known = "scenes, sets";
  for (const ParamSpec& p : info.params) known += ", " + p.name;
  fail(where,
       "technique '" + info.name + "' has no parameter '" + key + "' (known: " + known + ")");
}

// sets = [{ a = 1, b = 2 }, ...]
std::vector<ParamValues> parse_sets(const toml::node& n, const Src& src,
                                    const TechniqueInfo& info) {
  const toml::array* a = n.as_array();
  if (!a || a->empty())
    fail(src.at(n), "'sets' must be a non-empty array of tables, e.g. [{ " +
                        std::string(info.params.empty() ? "param" : info.params[0].name) +
                        " = 1 }]");
  std::vector<ParamValues> sets;
  for (const toml::node& e : *a) {
    const toml::table* t = e.as_table();
    if (!t || t->empty()) fail(src.at(e), "each of 'sets' must be a table of parameter values");
    ParamValues set;
    for (auto&& [k, v] : *t) {
      const std::string key(k.str());
      const ParamSpec* spec = find_param(info, key);
      if (!spec) unknown_param(info, src.at(v), key);
      const double value =
          spec->kind == ParamKind::Bool ? number_or_flag(v, src, key) : number(v, src, key);
      check_param_value(*spec, value, src.at(v) + ": technique '" + info.name + "'");
      set[key] = value;
    }
    sets.push_back(set);
  }
  return sets;
}

std::string describe_setting(const TechniqueInfo& info, const ParamValues& values) {
  std::string out;
  for (const ParamSpec& p : info.params)
    out += (out.empty() ? "" : ", ") + p.name + " = " + format_param(p, values.at(p.name));
  return out.empty() ? "defaults" : out;
}

}  // namespace

TechniqueSweep parse_technique(const toml::table& t, const Src& src, const toml::node& node) {
  TechniqueSweep ts;
  ts.where = src.at(node);
  if (!t.contains("name")) fail(ts.where, "[[technique]] needs a 'name'");
  ts.name = string_of(*t.get("name"), src, "name");
  const TechniqueEntry* entry = TechniqueRegistry::instance().find(ts.name);
  if (!entry) {
    std::string known;
    for (const auto& n : TechniqueRegistry::instance().names())
      known += (known.empty() ? "" : ", ") + n;
    fail(src.at(*t.get("name")), "unknown technique '" + ts.name + "' (known: " + known + ")");
  }
  for (auto&& [k, v] : t) {
    const std::string key(k.str());
    if (key == "name") continue;
    if (key == "scenes") {
      ts.scenes = string_list(v, src, key);
      continue;
    }
    if (key == "sets") {
      ts.sets = parse_sets(v, src, entry->info);
      continue;
    }
    const ParamSpec* spec = find_param(entry->info, key);
    if (!spec) unknown_param(entry->info, src.at(v), key);
    std::vector<double> values = number_list(v, src, key, spec->kind == ParamKind::Bool);
    for (double value : values)
      check_param_value(*spec, value, src.at(v) + ": technique '" + ts.name + "'");
    ts.param_lists[key] = values;
  }
  for (const ParamValues& set : ts.sets)
    for (const auto& [key, value] : set)
      if (ts.param_lists.count(key))
        fail(src.at(*t.get("sets")), "technique '" + ts.name + "': parameter '" + key +
                                         "' is both listed and in 'sets'; give it in one place");
  return ts;
}

std::vector<ParamValues> parameter_settings(const TechniqueSweep& ts) {
  const TechniqueInfo& info = TechniqueRegistry::instance().find(ts.name)->info;
  std::vector<ParamValues> settings = {ParamValues{}};
  for (const ParamSpec& p : info.params) {
    auto it = ts.param_lists.find(p.name);
    const std::vector<double> values =
        it != ts.param_lists.end() ? it->second : std::vector<double>{p.default_value};
    std::vector<ParamValues> next;
    for (const ParamValues& s : settings)
      for (double v : values) {
        ParamValues n = s;
        n[p.name] = v;
        next.push_back(n);
      }
    settings = next;
  }
  if (ts.sets.empty()) return settings;
  std::vector<ParamValues> paired;
  for (const ParamValues& s : settings)
    for (const ParamValues& set : ts.sets) {
      ParamValues n = s;
      for (const auto& [key, value] : set) n[key] = value;
      paired.push_back(n);
    }
  return paired;
}

void check_technique_sweep(const TechniqueSweep& ts, const std::vector<SceneDesc>& scenes) {
  std::set<std::string> scene_names;
  for (const SceneDesc& s : scenes) scene_names.insert(s.name);
  for (const std::string& s : ts.scenes)
    if (!scene_names.count(s))
      fail(ts.where, "technique '" + ts.name + "' names unknown scene '" + s + "'");
  const TechniqueInfo& info = TechniqueRegistry::instance().find(ts.name)->info;
  // Effects: every scene this technique runs on must ask only for effects it simulates.
  for (const SceneDesc& s : scenes) {
    if (!ts.runs_on(s.name)) continue;
    const std::string why = cannot_render(info, s);
    if (!why.empty())
      fail(ts.where, "technique '" + ts.name + "' cannot render scene '" + s.name + "': " + why +
                         "; restrict it with scenes = [...]");
  }
  // Every setting through the plugin's own checks, before any work.
  for (const ParamValues& setting : parameter_settings(ts)) {
    const std::string where = ts.where + " (" + describe_setting(info, setting) + ")";
    const ParamValues resolved = TechniqueRegistry::instance().resolve(ts.name, setting, where);
    if (!info.setting_cannot_render) continue;
    for (const SceneDesc& s : scenes) {
      if (!ts.runs_on(s.name)) continue;
      const std::string why = info.setting_cannot_render(resolved, s);
      if (!why.empty())
        fail(where, "technique '" + ts.name + "' cannot render scene '" + s.name + "': " + why);
    }
  }
}

}  // namespace rl
