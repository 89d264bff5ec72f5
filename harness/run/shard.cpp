#include "run/shard.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/atomic_write.h"
#include "core/columns.h"
#include "core/data_paths.h"
#include "core/error.h"
#include "core/hash.h"
#include "output/result_store.h"
#include "output/run_folder.h"
#include "run/cell_provenance.h"
#include "run/runner.h"

namespace rl {
namespace fs = std::filesystem;

ShardSpec parse_shard(const std::string& text) {
  ShardSpec s;
  const size_t slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    size_t a = 0, b = 0;
    s.index = std::stoi(text.substr(0, slash), &a);
    s.count = std::stoi(text.substr(slash + 1), &b);
    if (a != slash || b != text.size() - slash - 1) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    throw ConfigError("--shard '" + text + "': give I/N, e.g. 0/4 for the first of four shards");
  }
  if (s.count < 1 || s.count > 10000 || s.index < 0 || s.index >= s.count)
    throw ConfigError("--shard '" + text + "': need 0 <= I < N <= 10000");
  return s;
}

double truth_group_cost(const SweepConfig& config, const std::vector<const Cell*>& group) {
  if (group.empty()) return 0;
  const SceneDesc& scene = config.scenes[group.front()->scene_index];
  const double pixels = double(group.front()->width) * group.front()->height;
  double rays_per_pixel = 1;
  if (scene.effects.has(Effect::AmbientOcclusion)) rays_per_pixel += scene.ao.samples;
  if (scene.effects.has(Effect::SelfShadow)) rays_per_pixel += 1;
  if (scene.effects.has(Effect::SceneShadows)) rays_per_pixel += 2;  // the relief, the objects
  // A truth ray costs about what a shaded pixel of a frame does on these machines (both are a
  // few hundred ns); each cell renders its G-buffer, warm-up and timed frames.
  double cost = pixels * rays_per_pixel;
  for (const Cell* c : group)
    cost += double(c->width) * c->height * (1 + config.warmup + config.frames);
  return cost;
}

std::vector<Cell> shard_cells(const SweepConfig& config, const std::vector<Cell>& cells,
                              const ShardSpec& shard) {
  if (!shard.active()) return cells;
  std::map<std::string, std::vector<const Cell*>> groups;
  for (const Cell& c : cells) groups[c.truth_key].push_back(&c);
  std::vector<std::pair<double, std::string>> by_cost;
  for (const auto& [key, g] : groups) by_cost.push_back({truth_group_cost(config, g), key});
  std::sort(by_cost.begin(), by_cost.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  std::vector<double> load(size_t(shard.count), 0.0);
  std::map<std::string, int> owner;
  for (const auto& [cost, key] : by_cost) {
    const int s = int(std::min_element(load.begin(), load.end()) - load.begin());
    load[size_t(s)] += cost;
    owner[key] = s;
  }
  std::vector<Cell> mine;
  for (const Cell& c : cells)
    if (owner[c.truth_key] == shard.index) mine.push_back(c);
  return mine;
}

namespace {

// What determines a sweep's cells: its canonical scenes and settings, and every cell's key
// (technique and parameters, view, viewport, texture resolution, measurement version), so
// shards of another sweep cannot merge. Runs recorded before the cells counted carry the
// first version (the canonical text alone), which is still read.
std::string config_hash(const SweepConfig& config) {
  std::string all = config.canonical;
  for (const Cell& c : expand_cells(config)) all += "|" + c.key;
  return "2:" + hex64(fnv1a64(all));
}

std::string config_hash_as_recorded(const SweepConfig& config, const std::string& recorded) {
  return recorded.rfind("2:", 0) == 0 ? config_hash(config) : hex64(fnv1a64(config.canonical));
}

nlohmann::json read_record(const std::string& dir) {
  const std::string path = dir + "/sweep.json";
  std::ifstream in(path);
  if (!in)
    throw ConfigError(dir +
                      ": no sweep.json (not the output folder of a relieflab run, or of "
                      "one older than sharding)");
  try {
    nlohmann::json j;
    in >> j;
    for (const char* k : {"config_hash", "text", "base_dir", "source", "shard"})
      if (!j.contains(k) || !j[k].is_string()) throw std::runtime_error(std::string("no ") + k);
    return j;
  } catch (const std::exception& e) {
    throw ConfigError(path + ": unreadable (" + e.what() + ")");
  }
}

// The shard a folder's run measured, from its sweep.json (an edited field is named as the
// file's, not as a --shard option the user never gave).
ShardSpec recorded_shard(const std::string& dir) {
  const std::string text = read_record(dir)["shard"].get<std::string>();
  try {
    return parse_shard(text);
  } catch (const ConfigError&) {
    throw ConfigError(dir + "/sweep.json: its 'shard' field '" + text +
                      "' is not I/N (was the file edited?)");
  }
}

}  // namespace

void write_sweep_record(const SweepConfig& config, const ShardSpec& shard,
                        const std::string& out_dir) {
  const nlohmann::json j = {{"name", config.name},         {"source", config.source},
                            {"base_dir", config.base_dir}, {"config_hash", config_hash(config)},
                            {"shard", shard.text()},       {"text", config.text}};
  write_text_atomic(out_dir + "/sweep.json", j.dump(2) + "\n");
}

void refuse_another_shard(const ShardSpec& shard, const std::string& out_dir) {
  if (!fs::exists(out_dir + "/sweep.json")) return;
  std::string recorded;
  try {
    recorded = read_record(out_dir)["shard"].get<std::string>();
  } catch (const ConfigError&) {
    return;  // a damaged record is rewritten by this run
  }
  if (recorded == shard.text()) return;
  auto what = [](const std::string& s) {
    return s == "0/1" ? std::string("the whole sweep") : "shard " + s;
  };
  throw ConfigError(out_dir + " holds a run of " + what(recorded) +
                    " (its sweep.json); this run measures " + what(shard.text()) +
                    ", and its rows.csv and tables would replace the folder's with those of " +
                    what(shard.text()) + " alone: give another --out (nothing was written)");
}

namespace {

// The config every folder ran (they must agree), rebuilt from the first one's record. One
// whose files read differently now is refused, unless `changed_files` is given: `status` then
// reports what a run of the config as it reads now would reuse, and sets it to say so.
SweepConfig recorded_config(const std::vector<std::string>& dirs, bool* changed_files = nullptr) {
  if (dirs.empty()) throw ConfigError("give the run's output folder(s)");
  const nlohmann::json first = read_record(dirs.front());
  for (const std::string& d : dirs) {
    const nlohmann::json r = read_record(d);
    if (r["config_hash"] != first["config_hash"])
      throw ConfigError(d + ": ran another config (" + r["source"].get<std::string>() +
                        ", config hash " + r["config_hash"].get<std::string>() + ") than " +
                        dirs.front() + " (" + first["source"].get<std::string>() + ", " +
                        first["config_hash"].get<std::string>() +
                        "); shards of one sweep must run the same config");
    if (!fs::exists(d + "/results.sqlite")) throw ConfigError(d + ": no results.sqlite");
  }
  SweepConfig config =
      parse_sweep_config(first["text"].get<std::string>(), first["source"].get<std::string>(),
                         first["base_dir"].get<std::string>());
  const std::string recorded = first["config_hash"].get<std::string>();
  if (changed_files) *changed_files = config_hash_as_recorded(config, recorded) != recorded;
  if (!changed_files && config_hash_as_recorded(config, recorded) != recorded)
    throw ConfigError(dirs.front() +
                      ": its config reads differently here (its files changed "
                      "since it ran?); config hash " +
                      config_hash_as_recorded(config, recorded) + " against " + recorded);
  return config;
}

// A merge writes into a new folder or one of the same sweep (a shard's own, or an earlier
// merge): the rows of another sweep would mix with these, and its tables be replaced. A store
// without sweep.json is a merge of this sweep killed before it wrote one (it writes the record
// first now) when every row in it is one of this sweep's cells: the merge resumes.
void refuse_another_sweep(const std::string& out_dir, const nlohmann::json& shards,
                          const std::vector<Cell>& cells) {
  if (fs::exists(out_dir + "/sweep.json")) {
    const nlohmann::json there = read_record(out_dir);
    if (there["config_hash"] != shards["config_hash"])
      throw ConfigError("merge: " + out_dir + " holds another sweep (" +
                        there["source"].get<std::string>() + ", config hash " +
                        there["config_hash"].get<std::string>() + ") than the shards (" +
                        shards["config_hash"].get<std::string>() +
                        "); merge into a new folder (nothing was written)");
  } else if (fs::exists(out_dir + "/results.sqlite") &&
             !store_creation_cut_short(out_dir + "/results.sqlite")) {
    std::set<std::string> keys;
    for (const Cell& c : cells) keys.insert(c.key);
    const ResultStore store(out_dir + "/results.sqlite", ResultStore::Access::ReadOnly);
    for (const std::string& k : store.keys())
      if (!keys.count(k))
        throw ConfigError("merge: " + out_dir +
                          " holds a result store but no sweep.json, with rows of cells this "
                          "sweep does not have (key " +
                          k +
                          "): not a run of this sweep; merge into a new folder (nothing "
                          "was written)");
  }
}

// Columns that differ between two measurements of one cell without either being wrong: times
// (and rates), texts (the renderer, file names) and whether a precompute came from the cache.
bool varies_between_runs(const ColumnSpec& c) {
  return c.unit == "ms" || c.unit == "1/s" || c.kind == ColumnKind::Text ||
         c.name.ends_with("_cached");
}

// Two shards (or a shard and an earlier merge) that measured one cell must agree on it but for
// its times: otherwise one was measured by another build or renderer, or edited, and keeping
// either without a word would publish a number the other contradicts.
void refuse_disagreeing_rows(const std::string& out_dir, const std::vector<std::string>& dirs,
                             const std::vector<Cell>& cells) {
  std::map<std::string, std::pair<nlohmann::ordered_json, std::string>> first;  // key: row, dir
  std::vector<std::string> sources = dirs;
  // A store whose making was cut short (a merge killed then) holds nothing to disagree with.
  if (fs::exists(out_dir + "/results.sqlite") &&
      !store_creation_cut_short(out_dir + "/results.sqlite"))
    sources.insert(sources.begin(), out_dir);
  for (const std::string& d : sources) {
    const ResultStore store(d + "/results.sqlite", ResultStore::Access::ReadOnly);
    const std::set<std::string> keys = store.keys();
    for (const Cell& c : cells) {
      if (!keys.count(c.key) || !stored_row_problem(store, c).empty()) continue;
      const nlohmann::ordered_json row = *store.row(c.key);
      auto [it, fresh] = first.emplace(c.key, std::make_pair(row, d));
      if (fresh) continue;
      const std::vector<std::string> parts =
          differing_parts(Provenance::parse(it->second.first.value("measured_from", "")),
                          Provenance::parse(row.value("measured_from", "")));
      if (!parts.empty() && parts.front() != "all") {
        std::string names;
        for (const std::string& p : parts) names += (names.empty() ? "" : ", ") + p;
        throw ConfigError("merge: " + it->second.second + " and " + d + " measured " + c.technique +
                          " (key " + c.key + ") from different " + names +
                          " (output/provenance.h); merge shards of one build and one set of "
                          "inputs (nothing was written)");
      }
      for (const DeclaredColumn& col : declared_columns()) {
        if (varies_between_runs(col.spec)) continue;
        const nlohmann::ordered_json& kept = it->second.first;
        const auto a = kept.find(col.spec.name), b = row.find(col.spec.name);
        const bool in_a = a != kept.end(), in_b = b != row.end();
        if (in_a == in_b && (!in_a || *a == *b)) continue;
        throw ConfigError("merge: " + it->second.second + " and " + d + " disagree on " +
                          c.technique + " (key " + c.key + "): '" + col.spec.name + "' is " +
                          (in_a ? a->dump() : "absent") + " in one and " +
                          (in_b ? b->dump() : "absent") +
                          " in the other (measured by another build or renderer, or edited?); "
                          "merge shards of one run (nothing was written)");
      }
    }
  }
}

// How many of `cells` have no row in `store`.
size_t missing_cells(const std::vector<Cell>& cells, const ResultStore& store) {
  const std::set<std::string> have = store.keys();
  size_t n = 0;
  for (const Cell& c : cells) n += !have.count(c.key);
  return n;
}

}  // namespace

RunStatus run_status(const std::vector<std::string>& dirs) {
  RunStatus s;
  const SweepConfig config = recorded_config(dirs, &s.files_changed);
  std::vector<Cell> cells = expand_cells(config);
  s.name = config.name;
  s.source = config.source;
  if (dirs.size() == 1) {
    const ShardSpec shard = recorded_shard(dirs.front());
    if (shard.active()) {
      cells = shard_cells(config, cells, shard);
      s.shard = shard.text();
    }
  }
  // A row counts as done when a run would reuse it: whole, and measured from what this build
  // and the files give now (a corrupt or stale one is measured again).
  std::set<std::string> have, stored, whole;
  const ProvenanceContext provenance = provenance_context(config, renderer_identity());
  std::map<std::string, size_t> reasons;
  for (const std::string& d : dirs) {
    const ResultStore store(d + "/results.sqlite", ResultStore::Access::ReadOnly);
    const std::set<std::string> keys = store.keys();
    std::set<std::string> usable;
    for (const Cell& c : cells)
      if (keys.count(c.key) && !have.count(c.key)) {
        stored.insert(c.key);
        if (stored_row_problem(store, c).empty()) usable.insert(c.key), whole.insert(c.key);
      }
    const ReusePlan plan = plan_reuse(config, cells, store, usable, provenance);
    have.insert(plan.reuse.begin(), plan.reuse.end());
    s.stale += plan.stale;
    for (const auto& [why, n] : plan.reasons) reasons[why] += n;
  }
  s.unusable = stored.size() - whole.size();
  for (const auto& [why, n] : reasons) s.stale_reasons.push_back({why, n});
  std::stable_sort(s.stale_reasons.begin(), s.stale_reasons.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  std::map<std::string, std::pair<size_t, size_t>> truths, techniques;
  std::vector<std::string> order;
  for (const Cell& c : cells) {
    const bool done = have.count(c.key) > 0;
    s.done += done;
    truths[c.truth_key].first += done;
    ++truths[c.truth_key].second;
    if (!techniques.count(c.technique)) order.push_back(c.technique);
    techniques[c.technique].first += done;
    ++techniques[c.technique].second;
  }
  s.cells = cells.size();
  s.truths = truths.size();
  for (const auto& [k, t] : truths) s.truths_done += t.first == t.second;
  for (const std::string& t : order) s.techniques.push_back({t, techniques[t]});
  return s;
}

size_t rewrite_outputs(const std::string& dir) {
  check_run_folder(dir);
  const SweepConfig config = recorded_config({dir});
  const RunFolderLock lock(dir);
  std::vector<Cell> cells = expand_cells(config);
  const ShardSpec shard = recorded_shard(dir);
  cells = shard_cells(config, cells, shard);
  const ResultStore store(dir + "/results.sqlite", ResultStore::Access::ReadOnly);
  // Rows under none of the sweep's keys were stored by a relieflab whose keys were made
  // otherwise (run/cells.cpp): rewriting from them would replace the folder's tables with empty
  // ones.
  const size_t stored = store.keys().size(), found = cells.size() - missing_cells(cells, store);
  if (stored > 0 && found == 0)
    throw ConfigError("report: " + dir + "/results.sqlite holds " + std::to_string(stored) +
                      " rows, none under this sweep's cell keys: they were measured by another "
                      "version of relieflab's measurement; run the sweep again (nothing was "
                      "rewritten)");
  return found - write_sweep_outputs(config, cells, store, dir);
}

std::string format_run_status(const RunStatus& s) {
  char line[512];
  std::snprintf(line, sizeof line,
                "sweep '%s' from %s%s: %zu of %zu cells done (%.1f%%), %zu of %zu truth traces "
                "complete\n",
                s.name.c_str(), s.source.c_str(),
                s.shard.empty() ? "" : (", shard " + s.shard).c_str(), s.done, s.cells,
                s.cells ? 100.0 * s.done / s.cells : 100.0, s.truths_done, s.truths);
  std::string out = line;
  if (s.files_changed)
    out +=
        "  its config's files read differently now than when it ran: counted as a run of "
        "the config as it reads now would count them\n";
  if (s.unusable)
    out += "  " + std::to_string(s.unusable) +
           " stored row(s) cannot stand for their cells (cut short, edited, or out of their "
           "columns' range): not counted; the next run measures them again\n";
  if (s.stale) {
    out += "  " + std::to_string(s.stale) +
           " stored row(s) were measured from other code or inputs: not counted; the next run "
           "measures them again:";
    for (size_t i = 0; i < s.stale_reasons.size(); ++i)
      out += std::string(i ? "," : "") + " " + s.stale_reasons[i].first + " (" +
             std::to_string(s.stale_reasons[i].second) + ")";
    out += "\n";
  }
  for (const auto& [t, c] : s.techniques) {
    std::snprintf(line, sizeof line, "  %-26s %zu / %zu\n", t.c_str(), c.first, c.second);
    out += line;
  }
  return out;
}

MergeSummary merge_shards(const std::string& out_dir, const std::vector<std::string>& shard_dirs) {
  if (shard_dirs.empty()) throw ConfigError("merge: give the shards' output folders");
  require_utf8_path(out_dir, "merge: the output folder");
  const SweepConfig config = recorded_config(shard_dirs);
  const std::vector<Cell> cells = expand_cells(config);
  refuse_another_sweep(out_dir, read_record(shard_dirs.front()), cells);
  fs::create_directories(out_dir);
  const RunFolderLock lock(out_dir);
  check_run_folder(out_dir);
  refuse_disagreeing_rows(out_dir, shard_dirs, cells);
  // The record first: a merge killed after this point is resumed by merging again.
  write_sweep_record(config, ShardSpec{}, out_dir);
  MergeSummary summary;
  summary.shards = shard_dirs.size();
  ResultStore store(out_dir + "/results.sqlite");
  for (const std::string& d : shard_dirs)
    summary.rows_added += store.merge_from(d + "/results.sqlite");
  summary.cells = cells.size();
  summary.missing = missing_cells(cells, store);
  summary.missing += write_sweep_outputs(config, cells, store, out_dir);  // unusable rows
  return summary;
}

}  // namespace rl
