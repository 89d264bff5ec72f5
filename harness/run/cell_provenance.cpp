#include "run/cell_provenance.h"

#include <algorithm>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "core/code_digest.h"
#include "core/error.h"
#include "core/hash.h"
#include "gl/context.h"
#include "relief/image_backend.h"
#include "technique/technique.h"

namespace rl {
namespace {

std::string digest_of(const std::string& text) {
  return hex64(fnv1a64(text));
}

// The weights model_frame_ms is predicted with ("none" without a model).
std::string cost_model_digest(const std::optional<CostModel>& model) {
  if (!model) return "none";
  std::string text = model->name + "|" + model->gpu;
  std::vector<double> weights = {model->frame_ms, model->pixel_ms, model->fragment_ms};
  weights.insert(weights.end(), model->op_ms.begin(), model->op_ms.end());
  for (double w : weights) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "|%.17g", w);
    text += buf;
  }
  return digest_of(text);
}

// Every file of the scene by role and content, and the reader that decodes its images: the
// same bytes read as a depth map and as a normal map are two surfaces. A scene of no image
// (procedural, or meshes alone) is decoded by no reader, and does not load one to say so.
std::string inputs_digest(const std::vector<SceneInput>& inputs) {
  std::string text = reads_images(inputs) ? "images through " + image_backend_name() : "no images";
  for (const SceneInput& in : inputs) text += "|" + in.role + "=" + in.digest;
  return digest_of(text);
}

// A built-in technique is its folder as built; a plugin's, its shared object; one registered
// elsewhere (a test's), its registering file as it is now; "" when none of them can be read.
std::string technique_code_digest(const TechniqueEntry& entry) {
  if (!entry.plugin.empty()) {
    const std::string bytes = file_digest(entry.plugin);
    return bytes.empty() ? "" : digest_of(std::string("plugin|") + bytes);
  }
  if (std::string built = folder_digest(source_folder(entry.source)); !built.empty()) return built;
  const std::string file = file_digest(entry.source);
  return file.empty() ? "" : digest_of(std::string(build_settings_digest()) + "|" + file);
}

}  // namespace

ProvenanceContext provenance_context(const SweepConfig& config, const std::string& renderer) {
  ProvenanceContext c;
  c.truth_code = code_digest({"harness/core", "harness/relief", "harness/scene", "harness/truth",
                              "harness/config", "harness/oiio", "harness/stb"});
  c.metrics_code = code_digest({"harness/metrics", "harness/run"});
  c.draw_code = code_digest({"harness/gl", "harness/gpu", "harness/technique"});
  c.renderer = digest_of(renderer);
  c.cost_model = cost_model_digest(config.cost_model);
  for (const auto& [scene, inputs] : config.scene_inputs) c.inputs[scene] = inputs_digest(inputs);
  for (const TechniqueSweep& t : config.techniques)
    if (const TechniqueEntry* e = TechniqueRegistry::instance().find(t.name))
      c.technique_code[t.name] = technique_code_digest(*e);
  return c;
}

Provenance cell_provenance(const ProvenanceContext& context, const SweepConfig& config,
                           const Cell& cell, const std::string& programs) {
  const std::string& scene = config.scenes[cell.scene_index].name;
  auto known = [](const std::map<std::string, std::string>& m, const std::string& k) {
    auto it = m.find(k);
    return it == m.end() || it->second.empty() ? std::string("unknown") : it->second;
  };
  Provenance p;
  p.parts = {{"inputs", known(context.inputs, scene)},
             {"truth_code", context.truth_code},
             {"metrics_code", context.metrics_code},
             {"draw_code", context.draw_code},
             {"technique_code", known(context.technique_code, cell.technique)},
             {"programs", programs.empty() ? "unknown" : programs},
             {"renderer", context.renderer},
             {"cost_model", context.cost_model}};
  return p;
}

std::string programs_text(const std::map<std::string, ProgramDesc>& programs) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& [key, d] : programs) {
    nlohmann::json defines = nlohmann::json::object();
    for (const auto& [k, v] : d.defines) defines[k] = v;
    list.push_back({{"owner", d.owner},
                    {"vertex", d.vertex_file},
                    {"geometry", d.geometry_file},
                    {"fragment", d.fragment_files},
                    {"defines", defines}});
  }
  return list.dump();
}

std::vector<ProgramDesc> parse_programs(const std::string& text) {
  std::vector<ProgramDesc> out;
  try {
    for (const nlohmann::json& p : nlohmann::json::parse(text)) {
      ProgramDesc d;
      d.owner = p.at("owner").get<std::string>();
      d.vertex_file = p.at("vertex").get<std::string>();
      d.geometry_file = p.at("geometry").get<std::string>();
      d.fragment_files = p.at("fragment").get<std::vector<std::string>>();
      for (const auto& [k, v] : p.at("defines").items()) d.defines[k] = v.get<std::string>();
      out.push_back(std::move(d));
    }
  } catch (const nlohmann::json::exception&) {
    return {};
  }
  return out;
}

std::string programs_digest(const std::vector<ProgramDesc>& programs) {
  if (programs.empty()) return "";
  std::vector<std::string> digests;
  try {
    for (const ProgramDesc& d : programs) digests.push_back(program_digest(d));
  } catch (const GlError&) {
    return "";  // a file it includes is gone: these are not the programs a run would draw
  }
  std::sort(digests.begin(), digests.end());
  std::string text;
  for (const std::string& d : digests) text += d + "|";
  return digest_of(text);
}

std::vector<std::string> provenance_changes(const Provenance& stored, const Provenance& now,
                                            const Cell& cell, const SweepConfig& config) {
  if (stored.parts.empty())
    return {"it was stored before rows recorded what they were measured from"};
  const std::string& scene = config.scenes[cell.scene_index].name;
  std::vector<std::string> why;
  for (const auto& [name, digest] : now.parts) {
    if (digest == "unknown") {
      why.push_back(name == "inputs" ? "the inputs of scene " + scene + " cannot be identified"
                    : name == "programs"
                        ? "the programs technique " + cell.technique + " drew are not on record"
                        : "the code of technique " + cell.technique + " cannot be identified");
      continue;
    }
    if (stored.part(name) == digest) continue;
    if (name == "inputs") why.push_back("the inputs of scene " + scene + " changed");
    if (name == "truth_code") why.push_back("the truth's code changed");
    if (name == "metrics_code") why.push_back("the metrics' code changed");
    if (name == "draw_code") why.push_back("the harness's drawing code changed");
    if (name == "technique_code")
      why.push_back("the code of technique " + cell.technique + " changed");
    if (name == "programs")
      why.push_back("the programs of technique " + cell.technique + " changed");
    if (name == "renderer") why.push_back("the renderer changed");
    if (name == "cost_model") why.push_back("the cost model changed");
  }
  return why;
}

std::string renderer_identity() {
  const GlContext& gl = GlContext::shared();
  return gl.renderer() + " | " + gl.version() + " | " +
         (gl.is_software() ? "wall clock + glFinish" : "GL_TIME_ELAPSED");
}

namespace {

// Why the row stored under `key` cannot stand for `cell` as measured now (empty: it can).
std::vector<std::string> stale_reasons(const SweepConfig& config, const Cell& cell,
                                       const std::string& key, const ResultStore& store,
                                       const ProvenanceContext& context) {
  const std::optional<nlohmann::ordered_json> row = store.row(key);
  if (!row) return {"it is missing"};
  const Provenance stored = Provenance::parse(row->value("measured_from", std::string()));
  const std::string programs = programs_digest(parse_programs(store.programs(key)));
  std::vector<std::string> why =
      provenance_changes(stored, cell_provenance(context, config, cell, programs), cell, config);
  for (std::string& w : why)
    if (w == "the renderer changed")
      w += " (the row's: " + row->value("renderer", std::string("?")) + ")";
  return why;
}

// The identity fields of `identity` as `row` holds them.
std::string identity_in(const nlohmann::ordered_json& row, const nlohmann::ordered_json& identity) {
  nlohmann::ordered_json id;
  for (const auto& [field, value] : identity.items())
    id[field] = row.value(field, nlohmann::ordered_json());
  return id.dump();
}

// Of the stored rows under no cell's key, those whose identity is a cell's in `unmatched`
// (cells without a usable row): cell key -> stored key.
std::map<std::string, std::string> rows_under_older_keys(const std::vector<Cell>& cells,
                                                         const ResultStore& store,
                                                         const std::set<std::string>& unmatched) {
  std::set<std::string> cell_keys;
  for (const Cell& c : cells) cell_keys.insert(c.key);
  std::map<std::string, const Cell*> by_identity;
  std::vector<const Cell*> shapes;  // one cell for each distinct set of identity fields
  std::set<std::string> seen_shapes;
  for (const Cell& c : cells) {
    if (!unmatched.count(c.key)) continue;
    by_identity.emplace(c.identity.dump(), &c);
    std::string shape;
    for (const auto& [field, value] : c.identity.items()) shape += field + "|";
    if (seen_shapes.insert(shape).second) shapes.push_back(&c);
  }
  std::map<std::string, std::string> out;
  if (by_identity.empty()) return out;
  for (const std::string& key : store.keys()) {
    if (cell_keys.count(key)) continue;
    std::optional<nlohmann::ordered_json> row;
    try {
      row = store.row(key);
    } catch (const nlohmann::json::exception&) {
      continue;
    }
    if (!row || !row->is_object()) continue;
    for (const Cell* shape : shapes) {
      auto it = by_identity.find(identity_in(*row, shape->identity));
      if (it == by_identity.end()) continue;
      out[it->second->key] = key;
      by_identity.erase(it);
      break;
    }
  }
  return out;
}

}  // namespace

ReusePlan plan_reuse(const SweepConfig& config, const std::vector<Cell>& cells,
                     const ResultStore& store, const std::set<std::string>& usable,
                     const ProvenanceContext& context) {
  ReusePlan plan;
  std::map<std::string, size_t> counts;
  std::vector<std::string> order;
  auto count = [&](const std::vector<std::string>& why) {
    ++plan.stale;
    for (const std::string& w : why)
      if (counts[w]++ == 0) order.push_back(w);
  };
  std::set<std::string> unmatched;
  for (const Cell& c : cells) {
    if (!usable.count(c.key)) {
      unmatched.insert(c.key);
      continue;
    }
    const std::vector<std::string> why = stale_reasons(config, c, c.key, store, context);
    if (why.empty())
      plan.reuse.insert(c.key);
    else
      count(why);
  }
  plan.replaces = rows_under_older_keys(cells, store, unmatched);
  for (const Cell& c : cells) {
    auto it = plan.replaces.find(c.key);
    if (it == plan.replaces.end()) continue;
    std::vector<std::string> why = stale_reasons(config, c, it->second, store, context);
    // What is in the key but in no part of the provenance: the scene's description (a reading
    // option, the base, an effect) or the sweep's timing and output settings.
    if (why.empty())
      why.push_back("the settings of scene " + config.scenes[c.scene_index].name +
                    " or of the sweep changed");
    count(why);
  }
  for (const std::string& w : order) plan.reasons.push_back({w, counts[w]});
  std::stable_sort(plan.reasons.begin(), plan.reasons.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  return plan;
}

std::string ReusePlan::summary() const {
  std::string s = std::to_string(reuse.size()) + " row(s) reused";
  if (!stale) return s;
  s += "; " + std::to_string(stale) + " re-measured: ";
  for (size_t i = 0; i < reasons.size(); ++i)
    s += (i ? ", " : "") + reasons[i].first + " (" + std::to_string(reasons[i].second) + ")";
  return s;
}

}  // namespace rl
