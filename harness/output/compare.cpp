#include "output/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <tuple>

#include "config/config_toml.h"
#include "core/columns.h"
#include "core/error.h"
#include "output/provenance.h"
#include "output/result_store.h"
#include "technique/technique.h"

namespace rl {

std::map<std::string, MetricTolerance> default_tolerances() {
  // What each column declares (core/columns.h): percentages of pixels a quarter of a point,
  // position errors and costs 2% of the value (they span decades across scenes), angles a
  // quarter degree, PSNR a quarter dB.
  std::map<std::string, MetricTolerance> out;
  for (const DeclaredColumn& c : declared_columns())
    if (c.spec.kind == ColumnKind::Number && c.spec.tolerance.watched())
      out[c.spec.name] = {c.spec.better != Better::Higher, c.spec.tolerance.abs,
                          c.spec.tolerance.rel};
  return out;
}

void read_tolerances(const std::string& path, std::map<std::string, MetricTolerance>& into) {
  // A FIFO or a device would block the reader or never end.
  if (!std::filesystem::is_regular_file(path))
    throw ConfigError(path + ": the tolerance file is not a regular file");
  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw ConfigError(path + ":" + std::to_string(e.source().begin.line) + ": " +
                      std::string(e.description()));
  }
  const Src src{path};
  check_keys(root, {"tolerances"}, src, "the tolerance file");
  const toml::table* t = root["tolerances"].as_table();
  if (!t) throw ConfigError(path + ": needs a [tolerances] table, e.g. wrong_pct = { abs = 0.5 }");
  for (auto&& [k, v] : *t) {
    const std::string name(k.str());
    if (!is_measured(name))
      fail(src.at(v), "'" + name + "' is not a measured column (" + measured_list() + ")");
    const toml::table* m = v.as_table();
    if (!m) fail(src.at(v), "'" + name + "' must be a table, e.g. { abs = 0.5, rel = 0.02 }");
    check_keys(*m, {"abs", "rel", "lower_is_better"}, src, "tolerance '" + name + "'");
    MetricTolerance tol = into.count(name) ? into[name] : MetricTolerance{};
    if (auto* n = m->get("abs")) tol.abs = number_in(*n, src, "abs", 0, 1e30);
    if (auto* n = m->get("rel")) tol.rel = number_in(*n, src, "rel", 0, 1e30);
    if (auto* n = m->get("lower_is_better")) {
      tol.lower_is_better = boolean_of(*n, src, name);
      // A column's direction is what its producer declares: a file that reversed it would turn
      // a regression into an improvement.
      const DeclaredColumn* col = find_column(name);
      if (col && col->spec.better != Better::Neither &&
          tol.lower_is_better != (col->spec.better == Better::Lower))
        fail(src.at(*n), "'" + name + "' is declared " +
                             (col->spec.better == Better::Lower ? "lower" : "higher") +
                             "-is-better (by " + col->producer +
                             "); a tolerance file cannot reverse it");
    }
    into[name] = tol;
  }
}

namespace {

// The technique's parameters as the row names them: each declared one where this process knows
// the technique, else the row's own `setting` (a plugin `compare` was not given).
std::string setting_of(const nlohmann::ordered_json& row) {
  const TechniqueEntry* e =
      TechniqueRegistry::instance().find(row.value("technique", std::string()));
  if (!e) return row.value("setting", std::string());
  std::string s;
  for (const ParamSpec& p : e->info.params)
    if (row.contains(p.name) && row[p.name].is_number())
      s += (s.empty() ? "" : " ") + p.name + "=" + format_param(p, row[p.name].get<double>());
  return s;
}

// What a cell is, whatever the config around it: technique, its parameters, scene, view,
// viewport, texture resolution (as the rows hold them).
std::string identity(const nlohmann::ordered_json& row) {
  nlohmann::ordered_json id;
  for (const char* f :
       {"technique", "scene", "elevation_deg", "azimuth_deg", "viewport", "texture_res"})
    id[f] = row.value(f, nlohmann::ordered_json());
  id["setting"] = setting_of(row);
  return id.dump();
}

std::string describe_cell(const nlohmann::ordered_json& row) {
  char view[64];
  std::snprintf(view, sizeof view, " el %g az %g", row.value("elevation_deg", 0.0),
                row.value("azimuth_deg", 0.0));
  std::string s = row.value("scene", std::string("?")) + view + " " +
                  row.value("viewport", std::string()) + " tex " +
                  row.value("texture_size", std::string());
  const std::string setting = setting_of(row);
  return setting.empty() ? s : s + " " + setting;
}

// The provenance parts two matched rows differ in, joined ("" when they agree, or when neither
// records one: two runs stored before rows did).
std::string provenance_difference(const nlohmann::ordered_json& b,
                                  const nlohmann::ordered_json& n) {
  const Provenance pb = Provenance::parse(b.value("measured_from", std::string()));
  const Provenance pn = Provenance::parse(n.value("measured_from", std::string()));
  if (pb.parts.empty() && pn.parts.empty()) return "";
  if (pb.parts.empty() || pn.parts.empty())
    return pb.parts.empty() ? "unrecorded in the base" : "unrecorded in the new run";
  std::string out;
  for (const std::string& part : differing_parts(pb, pn)) out += (out.empty() ? "" : ", ") + part;
  return out;
}

bool number_at(const nlohmann::ordered_json& row, const std::string& k, double& v) {
  if (!row.contains(k) || !row[k].is_number()) return false;
  v = row[k].get<double>();
  return std::isfinite(v);
}

void compare_cell(const nlohmann::ordered_json& b, const nlohmann::ordered_json& n,
                  const std::map<std::string, MetricTolerance>& tolerances, Comparison& out) {
  const std::string differs = provenance_difference(b, n);
  if (!differs.empty()) ++out.measured_from_differs[differs];
  for (const auto& [metric, tol] : tolerances) {
    double vb = 0, vn = 0;
    const bool has_b = number_at(b, metric, vb), has_n = number_at(n, metric, vn);
    if (!has_b && !has_n) continue;
    const std::string technique = n.value("technique", std::string("?"));
    if (has_b != has_n) {
      // An error column that became empty (nothing measured) or appeared: a change to see.
      (has_b ? out.worse : out.better)
          .push_back(
              {technique, metric, describe_cell(n), has_b ? vb : NAN, has_n ? vn : NAN, differs});
      continue;
    }
    const double worse_by = tol.lower_is_better ? vn - vb : vb - vn;
    const double allowed = std::max(tol.abs, tol.rel * std::abs(vb));
    if (worse_by > allowed)
      out.worse.push_back({technique, metric, describe_cell(n), vb, vn, differs});
    if (-worse_by > allowed)
      out.better.push_back({technique, metric, describe_cell(n), vb, vn, differs});
  }
}

}  // namespace

std::map<std::string, nlohmann::ordered_json> read_run_rows(const std::string& dir) {
  const std::string path = dir + "/results.sqlite";
  if (!std::filesystem::exists(path))
    throw ConfigError(dir + ": no results.sqlite (is it a relieflab run's output folder?)");
  const ResultStore store(path, ResultStore::Access::ReadOnly);
  std::map<std::string, nlohmann::ordered_json> rows;
  for (const std::string& k : store.keys()) {
    try {
      if (auto r = store.row(k)) {
        // A value its column cannot take (a wrong_pct of -1 would count as better than any
        // measurement) is an error naming the row: the store was edited or damaged.
        if (const std::string why = stored_value_outside_range(*r); !why.empty())
          throw ConfigError(path + ": the row of " + r->value("technique", std::string("?")) + " " +
                            describe_cell(*r) + " (key " + k + ") " + why +
                            " (was the store edited?)");
        rows[k] = *r;
      }
    } catch (const nlohmann::json::exception&) {
      // A row cut short counts as missing: a new run missing a base cell fails the comparison.
      std::fprintf(stderr,
                   "relieflab: warning: %s: the row of key %s is not valid JSON; left out\n",
                   path.c_str(), k.c_str());
    }
  }
  return rows;
}

Comparison compare_rows(const std::map<std::string, nlohmann::ordered_json>& base,
                        const std::map<std::string, nlohmann::ordered_json>& now,
                        const std::map<std::string, MetricTolerance>& tolerances) {
  Comparison c;
  std::map<std::string, const nlohmann::ordered_json*> base_left, new_left;  // by identity
  for (const auto& [key, row] : now) {
    auto it = base.find(key);
    if (it != base.end()) {
      ++c.matched_by_key;
      compare_cell(it->second, row, tolerances, c);
    } else {
      new_left[identity(row)] = &row;
    }
  }
  for (const auto& [key, row] : base)
    if (!now.count(key)) base_left[identity(row)] = &row;
  for (const auto& [id, row] : new_left) {
    auto it = base_left.find(id);
    if (it == base_left.end()) {
      c.only_new.push_back(row->value("technique", std::string("?")) + " " + describe_cell(*row));
      continue;
    }
    ++c.matched_by_identity;
    compare_cell(*it->second, *row, tolerances, c);
    base_left.erase(it);
  }
  for (const auto& [id, row] : base_left)
    c.only_base.push_back(row->value("technique", std::string("?")) + " " + describe_cell(*row));
  auto order = [](const CellChange& a, const CellChange& b) {
    return std::tie(a.technique, a.metric, a.cell) < std::tie(b.technique, b.metric, b.cell);
  };
  std::sort(c.worse.begin(), c.worse.end(), order);
  std::sort(c.better.begin(), c.better.end(), order);
  return c;
}

Comparison compare_runs(const std::string& base_dir, const std::string& new_dir,
                        const std::map<std::string, MetricTolerance>& tolerances) {
  return compare_rows(read_run_rows(base_dir), read_run_rows(new_dir), tolerances);
}

std::string format_comparison(const Comparison& c) {
  std::string out;
  char line[512];
  auto section = [&](const char* title, const std::vector<CellChange>& changes) {
    if (changes.empty()) return;
    std::snprintf(line, sizeof line, "%s (%zu):\n", title, changes.size());
    out += line;
    std::string group;
    for (const CellChange& ch : changes) {
      const std::string g = ch.technique + " / " + ch.metric;
      if (g != group) {
        out += "  " + g + "\n";
        group = g;
      }
      std::snprintf(line, sizeof line, "    %s: %.6g -> %.6g", ch.cell.c_str(), ch.base, ch.now);
      out += line;
      out += ch.measured_from.empty() ? "\n" : " (measured from other " + ch.measured_from + ")\n";
    }
  };
  section("WORSE beyond tolerance", c.worse);
  section("better beyond tolerance", c.better);
  auto one_side = [&](const char* title, const std::vector<std::string>& cells) {
    if (cells.empty()) return;
    std::snprintf(line, sizeof line, "%s (%zu):\n", title, cells.size());
    out += line;
    for (const std::string& s : cells) out += "    " + s + "\n";
  };
  one_side("only in the base run", c.only_base);
  one_side("only in the new run", c.only_new);
  if (!c.measured_from_differs.empty()) {
    size_t n = 0;
    for (const auto& [parts, cells] : c.measured_from_differs) n += cells;
    out += std::to_string(n) +
           " matched cell(s) were measured from other code or inputs (output/provenance.h):\n";
    for (const auto& [parts, cells] : c.measured_from_differs)
      out += "    " + std::to_string(cells) + " differ in " + parts + "\n";
  }
  const std::string incomplete = c.incomplete();
  std::snprintf(line, sizeof line,
                "%zu cells matched (%zu by key, %zu by identity): %zu worse, %zu better, %zu "
                "only in base, %zu only in new -> %s",
                c.matched_by_key + c.matched_by_identity, c.matched_by_key, c.matched_by_identity,
                c.worse.size(), c.better.size(), c.only_base.size(), c.only_new.size(),
                c.regressed()        ? "REGRESSED"
                : incomplete.empty() ? "ok"
                                     : "INCOMPLETE");
  out += line;
  if (!incomplete.empty()) out += ": " + incomplete;
  return out + "\n";
}

std::string Comparison::incomplete() const {
  if (matched_by_key + matched_by_identity == 0)
    return "no cell of the base run is in the new run (an empty run, or another sweep)";
  if (!only_base.empty() && !allow_missing)
    return std::to_string(only_base.size()) +
           " cell(s) of the base run are missing from the new run (one shard of several, or a "
           "run cut short; --allow-missing compares a subset on purpose)";
  return "";
}

}  // namespace rl
