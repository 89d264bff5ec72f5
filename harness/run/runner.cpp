#include "run/runner.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include <glm/glm.hpp>

#include "core/data_paths.h"
#include "core/elapsed.h"
#include "core/error.h"
#include "gl/context.h"
#include "gl/frame_timer.h"
#include "gl/render_target.h"
#include "metrics/fragment_cost.h"
#include "metrics/metrics.h"
#include "output/gbuffer_export.h"
#include "output/pareto.h"
#include "output/report.h"
#include "output/result_store.h"
#include "output/run_folder.h"
#include "output/tables.h"
#include "relief/cell_complex.h"
#include "relief/heightfield_faces.h"
#include "relief/image_io.h"
#include "relief/meta_relief.h"
#include "run/asset_check.h"
#include "run/cells.h"
#include "run/memory_estimate.h"
#include "scene/base_mesh.h"
#include "scene/relief_asset.h"
#include "technique/technique.h"
#include "truth/ao_truth_cache.h"
#include "truth/make_truth.h"
#include "truth/truth_render.h"

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

std::vector<float> rgb_of(const GBuffer& g) {
  std::vector<float> rgb(g.size() * 3);
  for (size_t i = 0; i < g.size(); ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = g.color[i][c];
  return rgb;
}

std::string describe_params(const Cell& c) {
  std::string s;
  for (const auto& [k, v] : c.params) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s=%g", k.c_str(), v);
    s += (s.empty() ? "" : " ") + std::string(buf);
  }
  return s;
}

// Everything built once per (scene, texture resolution).
struct Asset {
  ReliefMap map;
  // The map the truth is built from where the scene asks for another resolution
  // (truth_resolution) or another colour map (truth_color_resolution); null: `map` itself.
  std::unique_ptr<ReliefMap> truth_map;
  const ReliefMap& truth_source() const { return truth_map ? *truth_map : map; }
  std::unique_ptr<GpuRelief> relief;
  std::unique_ptr<GpuBase> base;
  std::unique_ptr<ObjectPass> objects;
  std::unique_ptr<SceneTruth> truth;
  double build_ms = 0;
  double texel_world = 0;  // world size of a texel on the base
  // The texel errors are measured in: the truth's where it has its own resolution, so that
  // every texture resolution of a scene is judged by one yardstick.
  double metric_texel = 0;
  // The base's fitted curvature against its closed form (sphere, torus): Figure 5.28.
  std::optional<CurvatureFitError> curvature_fit;
  double ao_ms = 0;  // the texture-space AO map's precompute (ambient_occlusion)
  bool ao_from_cache = false;
  // Prepared technique instances by (technique, parameters): prepare() runs once per asset.
  std::map<std::string, std::pair<std::unique_ptr<Technique>, double>> prepared;
};

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
  return "";
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

std::string stored_row_problem(const ResultStore& store, const Cell& cell) {
  std::string problem;
  usable_stored_row(store, cell, problem);
  return problem;
}

// The run log's line for a built asset: its size, build time and what its truth is.
std::string describe_asset(const SceneDesc& scene, const Asset& asset) {
  char buf[320];
  const char* unit = scene.base.curved() && (!has_charts(scene.base) || scene.meta.active())
                         ? "base triangle"
                         : "texel";
  // A meta-relief's size is its layer 0's (its bake, `map`, may differ).
  const MapSize layer0_size = asset.map.meta ? MapSize{asset.map.meta->layers()[0].map.width,
                                                       asset.map.meta->layers()[0].map.height}
                                             : MapSize{asset.map.width, asset.map.height};
  if (const CellComplex* cc = asset.map.cells.get())
    std::snprintf(buf, sizeof buf,
                  "relieflab: asset %s: cell complex %d^3, %ld grey cells, %ld domain faces "
                  "of %dx%d, classified in %.0f ms, sampled in %.0f ms (%.0f ms with the grid "
                  "choice%s), %.1f%% occluded fragments (Embree truth of the mesh %.0f ms)",
                  scene.name.c_str(), cc->grid(), cc->stats().grey_cells, cc->stats().domain_faces,
                  cc->resolution(), cc->resolution(), cc->stats().classify_ms,
                  cc->stats().sample_ms, cc->stats().construction_ms,
                  cc->stats().from_cache ? "; read from the precompute cache" : "",
                  100.0 * cc->stats().occluded_ratio(), asset.truth->build_ms());
  else if (scene.meta.active() && !scene.base.curved())
    std::snprintf(buf, sizeof buf,
                  "relieflab: asset %s at %dx%d (bake %dx%d): built in %.0f ms (truth: the "
                  "%zu-layer meta-relief traced exactly)",
                  scene.name.c_str(), layer0_size.width, layer0_size.height, asset.map.width,
                  asset.map.height, asset.build_ms, scene.meta.layers.size() + 1);
  else if (asset.truth->tessellation_bound() == 0 && !scene.base.curved())
    std::snprintf(buf, sizeof buf,
                  "relieflab: asset %s at %dx%d: built in %.0f ms (truth %.0f ms, exact to "
                  "rounding: each trace states its bound in texels)",
                  scene.name.c_str(), layer0_size.width, layer0_size.height, asset.build_ms,
                  asset.truth->build_ms());
  else
    std::snprintf(buf, sizeof buf,
                  "relieflab: asset %s at %dx%d: built in %.0f ms (Embree truth %.0f ms, "
                  "tessellation %dx%d per %s, deviation <= %.2g depth units)",
                  scene.name.c_str(), layer0_size.width, layer0_size.height, asset.build_ms,
                  asset.truth->build_ms(), asset.truth->subdivision(), asset.truth->subdivision(),
                  unit, asset.truth->tessellation_bound());
  return buf;
}

// The run log's statement of a truth trace's accuracy in the headline's units.
std::string describe_truth_bound(const GBuffer& truth, double texel_world) {
  const TruthBoundStats s = truth_bound_stats(truth, texel_world);
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "relieflab: truth bound at this view: <= %.3g texels on every hit; %ld of %ld "
                "pixels (%.3g%%) above the %.2g-texel target",
                s.largest_texels, s.uncertain, s.covered,
                s.covered ? 100.0 * double(s.uncertain) / double(s.covered) : 0.0,
                kTruthBoundTarget);
  return buf;
}

// A cell complex's construction (Apaza & Andujar, Table 1) and ray throughput (Table 2):
// intersections per second are the pixels the technique covers over the median frame time.
void add_cell_columns(Row& row, const CellComplex& cc, const GBuffer& g, double frame_ms) {
  const CellComplex::Stats& st = cc.stats();
  row["cell_grid"] = cc.grid();
  row["mesh_faces"] = double(st.mesh_triangles);
  row["grey_cells"] = double(st.grey_cells);
  row["domain_faces"] = double(st.domain_faces);
  row["cell_bytes"] = double(cc.gpu_bytes());
  row["cell_classify_ms"] = st.classify_ms;
  row["cell_sample_ms"] = st.sample_ms;
  row["cell_construction_ms"] = st.construction_ms;  // the build's, also when read from cache
  row["cell_from_cache"] = st.from_cache;
  row["cell_distance_bytes"] = double(cc.distance_bytes());
  row["cell_ambiguous_regions"] = double(st.ambiguous_regions);
  row["occluded_fragment_pct"] = 100.0 * st.occluded_ratio();
  const double texels = double(st.domain_faces) * cc.resolution() * cc.resolution();
  row["multi_crossing_pct"] = texels > 0 ? 100.0 * double(st.multi_crossing_texels) / texels : 0.0;
  std::string trials;
  for (const GridTrial& t : st.trials) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%s%d:%.3g", trials.empty() ? "" : " ", t.grid,
                  100.0 * t.occluded_ratio);
    trials += buf;
  }
  row["grid_trials"] = trials;  // N:occluded % of each step of an automatic choice
  long covered = 0;
  for (size_t i = 0; i < g.size(); ++i) covered += g.covered(i);
  row["intersections_per_s"] = frame_ms > 0 ? double(covered) / (frame_ms * 1e-3) : 0.0;
}

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
  log.line("relieflab: sweep '" + config.name + "' from " + config.source + ": " +
           std::to_string(summary.cells) + " cells" +
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

// ---- assets ---------------------------------------------------------------------------------

// The map (and the truth's own map where truth_resolution asks for one), the base, the truth,
// the texel sizes, the AO map and the GPU textures of one (scene, texture resolution). With
// `progress`, each stage is announced on stderr as it starts: a cell complex or an AO map can
// take minutes, and the per-cell progress line says nothing until the first cell is done.
std::unique_ptr<Asset> build_asset(const SweepConfig& config, const SceneDesc& scene,
                                   const Cell& cell, bool progress) {
  const auto t0 = Clock::now();
  auto stage = [&](const char* what) {
    if (progress)
      std::fprintf(stderr, "relieflab: scene %s at texture_res %d: %s (%.1f s so far)\n",
                   scene.name.c_str(), cell.texture_res, what, ms_since(t0) / 1000.0);
  };
  auto asset = std::make_unique<Asset>();
  stage(scene.relief.cells.active ? "building the relief (a cubic cell complex)"
                                  : "building the relief map");
  asset->map = build_relief_asset(scene, cell.texture_res);
  // The truth's own map where the scene gives it another depth resolution (truth_resolution)
  // or another colour map (truth_color_resolution).
  const int truth_res = scene.truth_texture_res > 0 ? scene.truth_texture_res : cell.texture_res;
  const int truth_color =
      scene.truth_color_texture_res > 0 ? scene.truth_color_texture_res : scene.color_texture_res;
  if (scene.relief.size_at(truth_res) != scene.relief.size_at(cell.texture_res) ||
      truth_color != scene.color_texture_res)
    asset->truth_map =
        std::make_unique<ReliefMap>(build_relief_asset(scene, truth_res, truth_color));
  asset->objects = std::make_unique<ObjectPass>(scene.objects);
  stage("building the truth's Embree scene");
  if (scene.base.curved()) {
    // One base mesh for the GPU, the truth and the texel size.
    const BaseMesh mesh = make_base_mesh(scene.base, scene.size, scene.tile);
    asset->curvature_fit = curvature_fit_error(scene.base, mesh);
    asset->base = std::make_unique<GpuBase>(base_geometry(mesh));
    asset->truth =
        std::make_unique<SceneTruth>(scene, asset->truth_source(), config.truth_tolerance, &mesh);
    // A meta-relief's texel is its layer 0's (its bake may be finer).
    const ReliefMap& layer0 = asset->map.meta ? asset->map.meta->layers()[0].map : asset->map;
    asset->texel_world = texel_world(mesh, MapSize{layer0.width, layer0.height});
    const ReliefMap& truth0 = asset->truth_source().meta
                                  ? asset->truth_source().meta->layers()[0].map
                                  : asset->truth_source();
    asset->metric_texel = texel_world(mesh, MapSize{truth0.width, truth0.height});
  } else {
    asset->base = std::make_unique<GpuBase>(make_base_geometry(scene));
    asset->truth =
        std::make_unique<SceneTruth>(scene, asset->truth_source(), config.truth_tolerance);
    asset->texel_world = texel_world(scene, cell.texture_res);
    asset->metric_texel = texel_world(
        scene, scene.truth_texture_res > 0 ? scene.truth_texture_res : cell.texture_res);
  }
  if (scene.drawn_effects().has(Effect::AmbientOcclusion))
    stage("computing the ambient occlusion map");
  const AoMap ao = attach_ao_map(asset->map, scene, asset->texel_world);
  asset->ao_ms = ao.compute_ms;
  asset->ao_from_cache = ao.from_cache;
  asset->relief = std::make_unique<GpuRelief>(asset->map, scene.meta.runtime());
  asset->build_ms = ms_since(t0);
  return asset;
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

struct TruthView {
  GBuffer g;
  TruthStats stats;
  GBuffer footprint;  // colour averaged over each pixel (footprint_samples > 1), else empty
};

// The truth of one (asset, viewport, view). The reference AO is most of an AO scene's truth:
// an earlier run's is reused where the hits are the same (truth/ao_truth_cache.h).
TruthView trace_truth(const SweepConfig& config, const SceneDesc& scene, const Asset& asset,
                      const Cell& cell, const Camera& camera) {
  std::optional<AoTruthCache> ao_cache;
  if (scene.effects.has(Effect::AmbientOcclusion))
    ao_cache.emplace(cell.truth_key, truth_source_hash(asset.truth_source()), ao_sampling(scene),
                     size_t(cell.width) * cell.height);
  TruthView t;
  t.g = asset.truth->render(asset.truth_source(), scene, camera, scene.effects, &t.stats,
                            ao_cache ? &*ao_cache : nullptr);
  if (ao_cache) ao_cache->save();
  if (const int n = config.footprint_samples; n > 1) {
    // The same view on a grid n times finer: n x n truth rays spread evenly over each pixel.
    const Camera fine = make_camera(scene, cell.view, cell.width * n, cell.height * n);
    t.footprint = footprint_color(
        asset.truth->render(asset.truth_source(), scene, fine, scene.effects, nullptr, nullptr), n);
  }
  return t;
}

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

// Where a cell's pictures and G-buffers go.
struct CellFiles {
  std::string image_dir, gbuffer_dir;
};

CellFiles cell_files(const RunOptions& options, const SceneDesc& scene) {
  return {options.out_dir + "/images/" + scene.name, options.out_dir + "/gbuffers/" + scene.name};
}

void write_truth_files(const SweepConfig& config, const CellFiles& files, const SceneDesc& scene,
                       const Cell& cell, const Camera& camera, const GBuffer& truth,
                       const GBuffer& footprint) {
  if (config.write_images)
    write_png(files.image_dir + "/truth_" + cell.truth_key + ".png", truth.width, truth.height, 3,
              rgb_of(truth));
  if (config.write_images && !footprint.color.empty())
    write_png(files.image_dir + "/truth_footprint_" + cell.truth_key + ".png", footprint.width,
              footprint.height, 3, rgb_of(footprint));
  if (config.write_gbuffers)
    write_gbuffer_exr(files.gbuffer_dir + "/truth_" + cell.truth_key + ".exr", truth, scene, camera,
                      {scene.name, "", "", cell.truth_key});
}

// ---- measure --------------------------------------------------------------------------------

// What one cell's technique drew and cost.
struct CellMeasure {
  GBuffer g;
  FragmentCost cost;
  ImageMetrics m;
  FrameTiming timing;
  std::vector<std::pair<std::string, double>> frame_columns;
  double precompute_ms = 0;
  bool precompute_cached = false;
  size_t technique_bytes = 0;
};

// The technique instance of a cell, prepared once per asset and parameter setting.
std::pair<std::unique_ptr<Technique>, double>& prepared_technique(const SweepConfig& config,
                                                                  const SceneDesc& scene,
                                                                  Asset& asset, const Cell& cell) {
  auto& slot = asset.prepared[cell.technique + "|" + describe_params(cell)];
  if (!slot.first) {
    slot.first = TechniqueRegistry::instance().create(cell.technique, cell.params, config.source);
    const auto t0 = Clock::now();
    slot.first->prepare_scene(scene, asset.map);
    glFinish();
    slot.second = ms_since(t0);
  }
  return slot;
}

CellMeasure measure_cell(const SweepConfig& config, const SceneDesc& scene, Asset& asset,
                         const Cell& cell, const Camera& camera, const GBuffer& truth,
                         bool software_gl) {
  auto& [technique, prepare_ms] = prepared_technique(config, scene, asset, cell);
  FrameInput frame{scene,
                   asset.map,
                   *asset.relief,
                   *asset.base,
                   camera,
                   scene.drawn_effects(),
                   asset.objects.get()};
  CellMeasure out;
  FragmentCounts counts;
  {
    RenderTarget target(cell.width, cell.height, RenderTarget::Kind::GBuffer);
    target.bind_and_clear();
    render_frame(*technique, frame, RenderTarget::Kind::GBuffer);
    target.read_back(out.g);
    target.read_back_costs(counts);
  }
  out.cost = fragment_cost(counts);
  out.frame_columns = technique->frame_columns();
  for (const auto& [name, value] : out.frame_columns) {
    const auto& declared = technique->info().columns;
    if (std::none_of(declared.begin(), declared.end(),
                     [&](const ColumnSpec& c) { return c.name == name; }))
      throw std::logic_error("technique '" + technique->info().name + "' wrote column '" + name +
                             "', which its describe() does not declare in .columns");
  }
  out.m = compare_gbuffers(out.g, truth, scene.depth, asset.metric_texel,
                           scene.effects.has(Effect::AmbientOcclusion));
  RenderTarget timing_target(cell.width, cell.height, RenderTarget::Kind::ColorOnly);
  out.timing = time_frames(
      [&] {
        timing_target.bind_and_clear();
        render_frame(*technique, frame, RenderTarget::Kind::ColorOnly);
      },
      config.warmup, config.frames, software_gl);
  out.precompute_ms = prepare_ms;
  out.precompute_cached = technique->prepared_from_cache();
  out.technique_bytes = technique->memory_bytes();
  return out;
}

// ---- row ------------------------------------------------------------------------------------

nlohmann::ordered_json number_or_empty(double value) {
  return std::isnan(value) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(value);
}

// The spread of view elevations over the covered pixels (planar bases: against the quad's
// plane), so a row's "elevation" is checked to mean one view angle.
void add_elevation_columns(Row& row, const SceneDesc& scene, const Camera& camera, const GBuffer& g,
                           const GBuffer& truth) {
  double elev_min = 90, elev_max = -90;
  if (!scene.base.curved())
    for (int y = 0; y < g.height; ++y)
      for (int x = 0; x < g.width; ++x) {
        const size_t i = size_t(y) * g.width + x;
        if (!g.covered(i) && !truth.covered(i)) continue;
        glm::dvec3 o, d;
        camera.pixel_ray(x, y, o, d);
        const double el = glm::degrees(std::asin(std::clamp(-d.z, -1.0, 1.0)));
        elev_min = std::min(elev_min, el);
        elev_max = std::max(elev_max, el);
      }
  const bool have = elev_min <= elev_max;
  row["elev_min_deg"] = have ? nlohmann::ordered_json(elev_min) : nlohmann::ordered_json();
  row["elev_max_deg"] = have ? nlohmann::ordered_json(elev_max) : nlohmann::ordered_json();
}

void add_timing_columns(Row& row, const Cell& cell, const FrameTiming& timing) {
  row["frame_ms"] = timing.median_ms;
  // Speed as the papers count it: frames per second (Baboud & Decoret, Policarpo et al.), and
  // viewport pixels x frames per second (Apaza & Andujar's "rays per second": every pixel of
  // the viewport, whether or not the relief covers it).
  row["fps"] = timing.median_ms > 0 ? 1e3 / timing.median_ms : 0.0;
  row["rays_per_s"] =
      timing.median_ms > 0 ? double(cell.width) * cell.height / (timing.median_ms * 1e-3) : 0.0;
  row["frame_ms_min"] = timing.min_ms;
  row["frame_ms_iqr"] = timing.iqr_ms;
  row["frames_timed"] = timing.frames;
  row["timing"] = timing.method;
}

// The representation's own columns: a multilayer bake (layers per texel, texels whose ray
// crossed more surfaces than that, the most crossings), a cell complex, a face set.
void add_representation_columns(Row& row, const Asset& asset, const CellMeasure& c) {
  const LayerStack& layers = asset.map.layers;
  const double texels = double(asset.map.width) * asset.map.height;
  row["layers"] = layers.count;
  row["layer_overflow_pct"] =
      layers.empty() ? nlohmann::ordered_json()
                     : nlohmann::ordered_json(100.0 * double(layers.overflow_texels) / texels);
  row["layer_odd_pct"] = layers.empty()
                             ? nlohmann::ordered_json()
                             : nlohmann::ordered_json(100.0 * double(layers.odd_texels) / texels);
  row["depth_complexity"] =
      layers.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(layers.max_crossings);
  if (!layers.empty() && asset.map.quantized) {
    row["normal_storage_err_mean_deg"] = layers.normal_storage_err_mean_deg;
    row["normal_storage_err_max_deg"] = layers.normal_storage_err_max_deg;
  }
  if (asset.map.cells) add_cell_columns(row, *asset.map.cells, c.g, c.timing.median_ms);
  if (asset.map.faces) row["face_count"] = asset.map.faces->count();
}

// Throws std::logic_error naming a column of `row` that no producer declares (core/columns.h)
// and that is not one of the cell's identity or parameter columns: tables, the report and the
// README's column reference know only declared columns.
void check_columns_declared(const Row& row, const Cell& cell) {
  for (const auto& [name, value] : row.items())
    if (!find_column(name) && !cell.identity.contains(name))
      throw std::logic_error("the row of cell " + cell.key + " holds column '" + name +
                             "', which no producer declares (core/columns.h)");
}

// Every measured column of a cell's row, beside its identity.
Row cell_row(const Cell& cell, const SceneDesc& scene, const Camera& camera, const Asset& asset,
             const CellMeasure& c, const TruthView& truth, const std::string& renderer) {
  Row row = cell.identity;
  // An error column that measures nothing (no pixel covered) is empty, never zero.
  for (const auto& [name, value] : c.m.named()) row[name] = number_or_empty(value);
  if (!truth.footprint.color.empty())
    for (const auto& [name, value] : footprint_metrics(c.g, truth.footprint)) row[name] = value;
  add_elevation_columns(row, scene, camera, c.g, truth.g);
  add_timing_columns(row, cell, c.timing);
  row["precompute_ms"] = c.precompute_ms;
  row["precompute_cached"] = c.precompute_cached;
  for (const auto& [name, value] : c.cost.named()) row[name] = number_or_empty(value);
  for (const auto& [name, value] : c.frame_columns) row[name] = value;
  row["memory_bytes"] = double(asset.relief->bytes() + c.technique_bytes);
  row["truth_subdivision"] = asset.truth->subdivision();
  row["truth_bound"] = asset.truth->tessellation_bound();
  row["truth_flagged"] = c.m.truth_flagged();
  row["truth_ms"] = truth.stats.trace_ms;
  row["truth_unresolved_px"] = double(truth.stats.unresolved);
  if (scene.effects.has(Effect::AmbientOcclusion)) {
    row["ao_precompute_ms"] = asset.ao_ms;
    row["ao_precompute_cached"] = asset.ao_from_cache;
    row["ao_rescale"] = scene.ao.rescale(scene.depth);
    row["ao_drawn"] = scene.ao.render;
    row["truth_ao_rays"] = double(truth.stats.ao_rays);
  }
  if (asset.curvature_fit) {
    row["curvature_fit_err_mean_pct"] = asset.curvature_fit->mean_pct;
    row["curvature_fit_err_max_pct"] = asset.curvature_fit->max_pct;
    row["curvature_sign_match_pct"] = asset.curvature_fit->sign_match_pct;
  }
  row["effects"] = join_effects(scene.effects);
  row["texture_size"] = std::to_string(asset.map.width) + "x" + std::to_string(asset.map.height);
  add_representation_columns(row, asset, c);
  // "sampled@1024": the truth of the map at another resolution (truth_resolution); "color@512":
  // with a colour map of its own (truth_color_resolution).
  std::string truth_label = truth_level_name(scene.truth);
  if (asset.truth_map && scene.truth_texture_res > 0)
    truth_label += "@" + std::to_string(scene.truth_texture_res);
  if (scene.truth_color_texture_res > 0)
    truth_label += " color@" + std::to_string(scene.truth_color_texture_res);
  row["truth"] = truth_label;
  row["renderer"] = renderer;
  row["key"] = cell.key;
  check_columns_declared(row, cell);
  return row;
}

// The cell's render and heat map (and raw G-buffer), and their paths in the row.
void write_cell_files(Row& row, const SweepConfig& config, const RunOptions& options,
                      const CellFiles& files, const SceneDesc& scene, const Cell& cell,
                      const Camera& camera, const GBuffer& g, const GBuffer& truth,
                      double metric_texel) {
  if (config.write_images) {
    const std::string render_png = files.image_dir + "/" + cell.key + "_render.png";
    const std::string error_png = files.image_dir + "/" + cell.key + "_error.png";
    write_png(render_png, g.width, g.height, 3, rgb_of(g));
    write_png(error_png, g.width, g.height, 3,
              error_heat_map(g, truth, metric_texel, config.heat_map_scale));
    row["image_render"] = fs::relative(render_png, options.out_dir).string();
    row["image_truth"] =
        fs::relative(files.image_dir + "/truth_" + cell.truth_key + ".png", options.out_dir)
            .string();
    row["image_error"] = fs::relative(error_png, options.out_dir).string();
  }
  if (config.write_gbuffers) {
    const std::string exr = files.gbuffer_dir + "/" + cell.key + ".exr";
    write_gbuffer_exr(exr, g, scene, camera,
                      {scene.name, cell.technique, describe_params(cell), cell.key});
    row["gbuffer"] = fs::relative(exr, options.out_dir).string();
    row["gbuffer_truth"] =
        fs::relative(files.gbuffer_dir + "/truth_" + cell.truth_key + ".exr", options.out_dir)
            .string();
  }
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
      asset = build_asset(config, scene, cell, options.progress);
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
                c.m.wrong_pct, c.m.pos_err.rmse, c.m.fetches.mean, c.timing.median_ms);
  return buf;
}

std::string done_line(const SweepSummary& summary, const RunOptions& options, size_t tables) {
  char buf[512];
  std::snprintf(
      buf, sizeof buf,
      "relieflab: done in %s: %zu cells, %zu new rows, %zu already done; traced truth "
      "%zu times, built %zu assets; wrote %s/rows.csv, %zu table(s), pareto.md and plots/",
      hms(summary.elapsed_s).c_str(), summary.cells, summary.new_rows, summary.already_done,
      summary.truth_traces, summary.asset_builds, options.out_dir.c_str(), tables);
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
  check_run_folder(options.out_dir);
  write_sweep_record(config, options.shard, options.out_dir);
  Log log(options.out_dir + "/run.log");
  ResultStore store(options.out_dir + "/results.sqlite");
  std::set<std::string> done = store.keys();
  const std::vector<std::string> dropped = drop_unusable_rows(store, cells, done);
  for (const Cell& c : cells) summary.already_done += done.count(c.key);
  GlContext& gl = GlContext::shared();
  summary.renderer = gl.renderer();
  log_plan(log, config, options, summary, all_cells.size(), duplicates, dropped, gl);
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
        measure_cell(config, scene, asset, cell, camera, truth.g, gl.is_software());
    if (measured.m.empty())
      log.line("relieflab: warning: " + cell.technique + " " + describe_params(cell) + " on " +
               scene.name + " el=" + std::to_string(cell.view.elevation_deg) +
               ": neither the technique nor the truth covers a pixel; its error columns are "
               "empty (nothing was measured)");
    Row row = cell_row(cell, scene, camera, asset, measured, truth, gl.renderer());
    write_cell_files(row, config, options, files, scene, cell, camera, measured.g, truth.g,
                     asset.metric_texel);
    store.insert(cell.key, row);
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
  write_text_atomic(out_dir + "/rows.csv", format_csv(rows, csv_columns(rows, leading)));
  for (const TableSpec& t : config.tables)
    write_text_atomic(out_dir + "/" + t.file, t.format == "latex" ? format_latex_table(rows, t)
                                                                  : format_markdown_table(rows, t));
  std::string fronts;
  for (const PlotSpec& p : config.plots)
    fronts += write_pareto_plots(rows, p, parameter_columns(config), out_dir) + "\n";
  write_text_atomic(out_dir + "/pareto.md", fronts);
  write_report(config, rows, parameter_columns(config), out_dir);
  return left_out;
}

}  // namespace rl
