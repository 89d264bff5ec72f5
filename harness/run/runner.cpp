#include "run/runner.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "core/data_paths.h"
#include "core/elapsed.h"
#include "core/error.h"
#include "gl/context.h"
#include "output/outputs_record.h"
#include "output/pareto.h"
#include "output/report.h"
#include "output/result_store.h"
#include "output/rows_csv.h"
#include "output/run_folder.h"
#include "output/tables.h"
#include "relief/cell_complex.h"
#include "relief/image_backend.h"
#include "run/asset_check.h"
#include "run/cell_provenance.h"
#include "run/cells.h"
#include "run/memory_estimate.h"
#include "run/sweep_stages.h"

namespace rl {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string hms(double seconds) {
  const long s = long(seconds + 0.5);
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  return buf;
}

// The run's log, appended to. Opened without following a link (check_run_folder refused one
// already; this closes the window between the check and the open).
class Log {
 public:
  explicit Log(const std::string& path)
      : fd_(::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644)) {
    if (fd_ < 0)
      throw ConfigError(path + ": cannot open the run log (" + std::strerror(errno) + ")");
  }
  ~Log() { ::close(fd_); }
  Log(const Log&) = delete;
  Log& operator=(const Log&) = delete;
  void line(const std::string& s) {
    std::fprintf(stderr, "%s\n", s.c_str());
    const std::string text = s + "\n";
    for (size_t done = 0; done < text.size();) {
      const ssize_t n = ::write(fd_, text.data() + done, text.size() - done);
      if (n <= 0) break;  // a full disk loses log lines, not the run
      done += size_t(n);
    }
  }

 private:
  int fd_;
};

// Why a parsed stored row cannot stand for `cell` ("" when it can).
std::string row_problem(const std::optional<nlohmann::ordered_json>& row, const Cell& cell) {
  if (!row) return "is missing";
  if (!row->is_object()) return "is not a JSON object";
  for (const auto& [field, value] : cell.identity.items()) {
    auto it = row->find(field);
    if (it == row->end() || *it != value) return "does not name the cell's '" + field + "'";
  }
  for (const DeclaredColumn& c : declared_columns()) {
    auto it = row->find(c.spec.name);
    if (it == row->end() || it->is_null()) continue;
    const bool flag = c.spec.kind == ColumnKind::Flag;
    if (c.spec.kind == ColumnKind::Number ? !it->is_number() : flag && !it->is_boolean())
      return std::string("holds a non-") + (flag ? "boolean" : "number") + " in '" + c.spec.name +
             "'";
  }
  return stored_value_outside_range(*row);
}

// The stored row of `cell` when it can stand for it; else nothing, and `problem` says why. The
// store is a file in the user's folder: an edit or a crash may have cut a row or changed its
// types, and a row that names another cell or holds text where a measure belongs must not be
// published.
std::optional<nlohmann::ordered_json> usable_stored_row(const ResultStore& store, const Cell& cell,
                                                        std::string& problem) {
  std::optional<nlohmann::ordered_json> row;
  try {
    row = store.row(cell.key);
  } catch (const nlohmann::json::exception& e) {
    problem = "is not valid JSON (" + std::string(e.what()).substr(0, 120) + ")";
    return std::nullopt;
  }
  problem = row_problem(row, cell);
  if (!problem.empty()) return std::nullopt;
  return row;
}

}  // namespace

std::string stored_row_problem(const ResultStore& store, const Cell& cell) {
  std::string problem;
  usable_stored_row(store, cell, problem);
  return problem;
}

namespace {

// ---- plan -----------------------------------------------------------------------------------

// Stored rows are checked before they are trusted: a corrupt one is dropped from the store and
// from `done` (its cell is measured again). Returns the log lines that say so.
std::vector<std::string> drop_unusable_rows(ResultStore& store, const std::vector<Cell>& cells,
                                            std::set<std::string>& done) {
  std::vector<std::string> dropped;
  for (const Cell& c : cells) {
    if (!done.count(c.key)) continue;
    const std::string problem = stored_row_problem(store, c);
    if (problem.empty()) continue;
    dropped.push_back("relieflab: warning: the stored row of " + c.technique + " / " +
                      c.identity.value("scene", std::string()) + " (key " + c.key + ") " + problem +
                      "; measuring the cell again");
    store.erase(c.key);
    done.erase(c.key);
  }
  return dropped;
}

void log_plan(Log& log, const SweepConfig& config, const RunOptions& options,
              const SweepSummary& summary, size_t all_cells, size_t duplicates,
              const std::vector<std::string>& dropped, GlContext& gl) {
  log.line(sweep_log_line_start(config.name, config.source) + std::to_string(summary.cells) +
           " cells" +
           (options.shard.active()
                ? " (shard " + options.shard.text() + " of " + std::to_string(all_cells) + ")"
                : std::string()) +
           ", " + std::to_string(summary.already_done) + " already in " + options.out_dir +
           "/results.sqlite");
  if (duplicates)
    log.line("relieflab: " + std::to_string(duplicates) +
             " repeated cell(s) dropped (the same view, setting and scene given twice: a repeated "
             "elevation, view or [[technique]] block)");
  for (const std::string& line : dropped) log.line(line);
  log.line("relieflab: OpenGL " + gl.version() + " on " + gl.renderer() + " (" + gl.platform() +
           "), frames timed by " +
           (gl.is_software() ? "wall clock + glFinish" : "GL_TIME_ELAPSED"));
  // The image module is loaded only for a sweep that reads or writes an image.
  bool any_image = config.write_images;
  for (const auto& [scene, inputs] : config.scene_inputs)
    any_image = any_image || reads_images(inputs);
  log.line(any_image ? "relieflab: image files through " + image_backend_description()
                     : std::string("relieflab: no image files read or written"));
  // Which file each surface of each scene comes from, and how it is read.
  for (const SceneDesc& scene : config.scenes) {
    auto it = config.scene_inputs.find(scene.name);
    if (it == config.scene_inputs.end() || it->second.empty()) continue;
    std::string line = "relieflab: scene " + scene.name + " reads";
    for (size_t i = 0; i < it->second.size(); ++i)
      line += std::string(i ? ";" : "") + " " + it->second[i].role + " from " + it->second[i].path;
    log.line(line);
  }
}

// Cells in order of (asset, truth), keeping the config's order otherwise: each asset is built
// and each truth traced once.
std::vector<size_t> measuring_order(const std::vector<Cell>& cells) {
  std::vector<size_t> order(cells.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::map<std::string, size_t> asset_rank, truth_rank;
  for (const Cell& c : cells) {
    asset_rank.emplace(c.asset_key, asset_rank.size());
    truth_rank.emplace(c.truth_key, truth_rank.size());
  }
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const Cell &ca = cells[a], &cb = cells[b];
    if (asset_rank[ca.asset_key] != asset_rank[cb.asset_key])
      return asset_rank[ca.asset_key] < asset_rank[cb.asset_key];
    return truth_rank[ca.truth_key] < truth_rank[cb.truth_key];
  });
  return order;
}

void log_asset(Log& log, const SceneDesc& scene, const Asset& asset) {
  log.line(describe_asset(scene, asset));
  if (const CellComplex* cc = asset.map.cells.get(); cc && cc->stats().ambiguous_regions)
    log.line("relieflab: warning: scene " + scene.name + ": " +
             std::to_string(cc->stats().ambiguous_regions) +
             " enclosed region(s) of the cell grid got disagreeing inside/outside votes (an "
             "open or non-manifold mesh); each was decided by the majority");
}

// ---- truth ----------------------------------------------------------------------------------

void log_truth(Log& log, const SceneDesc& scene, const Cell& cell, const TruthView& t,
               double metric_texel, size_t number) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "relieflab: truth #%zu traced: %s el=%g az=%g %dx%d: %llu primary + %llu "
                "shadow + %llu AO rays in %.0f ms",
                number, scene.name.c_str(), cell.view.elevation_deg, cell.view.azimuth_deg,
                cell.width, cell.height, (unsigned long long)t.stats.primary_rays,
                (unsigned long long)t.stats.shadow_rays, (unsigned long long)t.stats.ao_rays,
                t.stats.trace_ms);
  log.line(buf + (t.stats.ao_cached_px ? " (AO of " + std::to_string(t.stats.ao_cached_px) +
                                             " pixels from the cache)"
                                       : std::string()));
  log.line(describe_truth_bound(t.g, metric_texel));
  if (t.stats.unresolved)
    log.line("relieflab: warning: " + std::to_string(t.stats.unresolved) +
             " truth rays passed the floor by rounding and were placed on it");
}

// ---- the loop's shared inputs ---------------------------------------------------------------

// The asset and the truth of the cell being measured. measuring_order() puts the cells of one
// asset, and of one truth, next to each other, so each asset is built and each truth traced
// once; a scene's truths at its fixed truth resolution are kept across its texture resolutions.
struct SharedInputs {
  std::unique_ptr<Asset> asset;
  TruthView truth;

  void update(const SweepConfig& config, const RunOptions& options, const Cell& cell,
              const Camera& camera, const CellFiles& files, Log& log, SweepSummary& summary) {
    const SceneDesc& scene = config.scenes[cell.scene_index];
    if (cell.asset_key != asset_key_) {
      const ProgramUses uses;
      asset = build_asset(config, scene, cell, options.progress);
      asset->programs = uses.programs();
      asset_key_ = cell.asset_key;
      truth_key_.clear();
      ++summary.asset_builds;
      log_asset(log, scene, *asset);
    }
    if (cell.scene_index != memo_scene_) {
      truth_memo_.clear();
      memo_scene_ = cell.scene_index;
    }
    if (cell.truth_key == truth_key_) return;
    truth_key_ = cell.truth_key;
    if (auto memo = truth_memo_.find(cell.truth_key); memo != truth_memo_.end()) {
      truth = memo->second;  // the same surface and view at another texture resolution
      return;
    }
    truth = trace_truth(config, scene, *asset, cell, camera);
    if (scene.truth_texture_res > 0) truth_memo_[cell.truth_key] = truth;
    log_truth(log, scene, cell, truth, asset->metric_texel, ++summary.truth_traces);
    write_truth_files(config, files, scene, cell, camera, truth.g, truth.footprint);
  }

 private:
  std::string asset_key_, truth_key_;
  std::map<std::string, TruthView> truth_memo_;  // this scene's, by truth key
  size_t memo_scene_ = size_t(-1);
};

// ---- progress -------------------------------------------------------------------------------

// Wall time per technique (its cells' measurement, truths and assets not included), for the
// progress line's slowest technique.
using TechniqueTimes = std::map<std::string, std::pair<double, size_t>>;

std::string progress_line(const Cell& cell, const SceneDesc& scene, const CellMeasure& c,
                          const SweepSummary& summary, size_t finished, size_t todo,
                          double elapsed_s, const TechniqueTimes& times) {
  const double eta = elapsed_s / finished * (todo - finished);
  std::string slowest;
  double slowest_ms = -1;
  for (const auto& [t, s] : times)
    if (s.first / s.second > slowest_ms) slowest = t, slowest_ms = s.first / s.second;
  char buf[640];
  std::snprintf(buf, sizeof buf,
                "[%zu/%zu] %3.0f%% %s elapsed, ~%s left, %zu truths traced, slowest %s "
                "%.0f ms/cell | %s %s | %s el=%g az=%g %dx%d | "
                "wrong=%.3g%% pos_err_rmse=%.4g fetches=%.1f frame=%.2fms",
                summary.already_done + finished, summary.cells,
                100.0 * (summary.already_done + finished) / summary.cells, hms(elapsed_s).c_str(),
                hms(eta).c_str(), summary.truth_traces, slowest.c_str(), slowest_ms,
                cell.technique.c_str(), describe_params(cell).c_str(), scene.name.c_str(),
                cell.view.elevation_deg, cell.view.azimuth_deg, cell.width, cell.height,
                c.m.at("wrong_pct"), c.m.at("pos_err_rmse"), c.m.at("fetches_mean"),
                c.timing.median_ms);
  return buf;
}

std::string done_line(const SweepSummary& summary, const RunOptions& options, size_t tables) {
  char buf[512];
  std::snprintf(
      buf, sizeof buf,
      "relieflab: done in %s: %zu cells, %zu new rows (%zu of them re-measured), %zu "
      "reused; traced truth %zu times, built %zu assets; wrote %s/rows.csv, %zu table(s), "
      "pareto.md and plots/",
      hms(summary.elapsed_s).c_str(), summary.cells, summary.new_rows, summary.remeasured,
      summary.already_done, summary.truth_traces, summary.asset_builds, options.out_dir.c_str(),
      tables);
  return buf;
}

}  // namespace

// Plan (cells, keys, shard, the rows already stored), then per cell: its asset, its truth, its
// measurement and its row, each stage handing the next a plain value; then the outputs.
SweepSummary run_sweep(const SweepConfig& config, const RunOptions& options) {
  const auto start = Clock::now();
  require_utf8_path(options.out_dir, "the output folder");
  require_utf8_path(config.source, "the config");
  require_utf8_path(config.base_dir, "the config's folder");
  SweepSummary summary;
  size_t duplicates = 0;
  const std::vector<Cell> all_cells = expand_cells(config, &duplicates);
  const std::vector<Cell> cells = shard_cells(config, all_cells, options.shard);
  summary.cells = cells.size();
  // Every image decoded and every mesh loaded before the output folder is touched.
  const std::vector<std::string> asset_warnings = check_sweep_assets(config);
  refuse_cells_beyond_memory(config, cells);  // sizes known once the files are read

  fs::create_directories(options.out_dir);
  const RunFolderLock lock(options.out_dir);
  check_run_folder(options.out_dir);
  refuse_another_shard(options.shard, options.out_dir);
  write_sweep_record(config, options.shard, options.out_dir);
  Log log(options.out_dir + "/run.log");
  ResultStore store(options.out_dir + "/results.sqlite");
  std::set<std::string> done = store.keys();
  const std::vector<std::string> dropped = drop_unusable_rows(store, cells, done);
  GlContext& gl = GlContext::shared();
  summary.renderer = gl.renderer();
  // A stored row is reused only where everything it was measured from is as it is now.
  const ProvenanceContext provenance = provenance_context(config, renderer_identity());
  const ReusePlan reuse = plan_reuse(config, cells, store, done, provenance);
  done = reuse.reuse;
  summary.already_done = reuse.reuse.size();
  summary.remeasured = reuse.stale;
  log_plan(log, config, options, summary, all_cells.size(), duplicates, dropped, gl);
  if (reuse.reuse.size() + reuse.stale > 0) log.line("relieflab: " + reuse.summary());
  for (const std::string& w : asset_warnings) log.line(w);

  const size_t todo = cells.size() - summary.already_done;
  size_t finished = 0;
  SharedInputs inputs;
  const auto work_start = Clock::now();
  TechniqueTimes technique_ms;

  for (size_t index : measuring_order(cells)) {
    const Cell& cell = cells[index];
    if (done.count(cell.key)) continue;
    const SceneDesc& scene = config.scenes[cell.scene_index];
    const Camera camera = make_camera(scene, cell.view, cell.width, cell.height);
    const CellFiles files = cell_files(options, scene);
    inputs.update(config, options, cell, camera, files, log, summary);
    Asset& asset = *inputs.asset;
    const TruthView& truth = inputs.truth;

    const auto cell_start = Clock::now();  // the technique's part of the cell, truth excluded
    const CellMeasure measured =
        measure_cell(config, scene, asset, cell, camera, truth, gl.is_software());
    if (measured.m.empty())
      log.line("relieflab: warning: " + cell.technique + " " + describe_params(cell) + " on " +
               scene.name + " el=" + std::to_string(cell.view.elevation_deg) +
               ": neither the technique nor the truth covers a pixel; its error columns are "
               "empty (nothing was measured)");
    if (!measured.fetch_bound_warning.empty()) {
      char where[96];
      std::snprintf(where, sizeof where, " (%s el=%g az=%g)", scene.name.c_str(),
                    cell.view.elevation_deg, cell.view.azimuth_deg);
      log.line(measured.fetch_bound_warning + where);
    }
    Row row = cell_row(cell, scene, camera, asset, measured, truth, gl.renderer());
    std::vector<ProgramDesc> programs;
    for (const auto& [k, p] : measured.programs) programs.push_back(p);
    row["measured_from"] =
        cell_provenance(provenance, config, cell, programs_digest(programs)).text();
    write_cell_files(row, config, options, files, scene, cell, camera, measured.g, truth.g,
                     asset.metric_texel);
    // Replaces a row measured from other code or inputs, in one statement.
    auto older = reuse.replaces.find(cell.key);
    store.put(cell.key, row, programs_text(measured.programs),
              older == reuse.replaces.end() ? "" : older->second);
    ++summary.new_rows;
    ++finished;
    auto& [ms, n] = technique_ms[cell.technique];
    ms += ms_since(cell_start);
    ++n;
    if (options.progress)
      std::fprintf(stderr, "%s\n",
                   progress_line(cell, scene, measured, summary, finished, todo,
                                 ms_since(work_start) / 1000.0, technique_ms)
                       .c_str());
  }

  write_sweep_outputs(config, cells, store, options.out_dir);
  summary.elapsed_s = ms_since(start) / 1000.0;
  log.line(done_line(summary, options, config.tables.size()));
  return summary;
}

size_t write_sweep_outputs(const SweepConfig& config, const std::vector<Cell>& cells,
                           const ResultStore& store, const std::string& out_dir) {
  // Outputs from the store, in the config's cell order: the rows of these cells only.
  std::vector<Row> rows;
  size_t left_out = 0;
  const std::set<std::string> stored = store.keys();
  for (const Cell& c : cells) {
    if (!stored.count(c.key)) continue;
    std::string problem;
    std::optional<nlohmann::ordered_json> row = usable_stored_row(store, c, problem);
    if (!row) {
      std::fprintf(stderr,
                   "relieflab: warning: the stored row of %s / %s (key %s) %s; left out of the "
                   "outputs (running the sweep into this folder measures it again)\n",
                   c.technique.c_str(), config.scenes[c.scene_index].name.c_str(), c.key.c_str(),
                   problem.c_str());
      ++left_out;
      continue;
    }
    rows.push_back(std::move(*row));
  }
  std::vector<std::string> leading = {"technique",   "scene",       "elevation_deg",
                                      "azimuth_deg", "texture_res", "viewport"};
  for (const auto& p : parameter_columns(config)) leading.push_back(p);
  // Each file's text, written and recorded with its digest (output/outputs_record.h).
  std::map<std::string, std::string> written;
  written["rows.csv"] = format_csv(rows, csv_columns(rows, leading));
  const std::vector<Row> read_back =
      rows_as_values(parse_rows_csv(written["rows.csv"], out_dir + "/rows.csv"));
  for (const TableSpec& t : config.tables) written[t.file] = format_table_file(read_back, t);
  std::string fronts;
  for (const PlotSpec& p : config.plots)
    fronts += write_pareto_plots(rows, p, parameter_columns(config), out_dir) + "\n";
  written["pareto.md"] = fronts;
  for (const auto& [name, text] : written) write_text_atomic(out_dir + "/" + name, text);
  write_report(config, rows, parameter_columns(config), out_dir);
  // The report too: it shows the rows' numbers, and an edit to it is one to the results.
  written["report.html"] = read_text(out_dir + "/report.html");
  write_outputs_record(out_dir, written);
  return left_out;
}

}  // namespace rl
