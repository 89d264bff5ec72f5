#pragma once
// The runner's stages (DESIGN.md, "Results"), each handing the next a plain value: the assets
// of a (scene, texture resolution) are built once (sweep_assets.cpp), the truth of an (asset,
// viewport, view) traced once (sweep_truth.cpp), each cell measured (sweep_measure.cpp) and
// written as a row with its pictures (sweep_row.cpp); runner.cpp plans the cells and runs them.
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "config/config.h"
#include "gl/frame_timer.h"
#include "gl/shader_library.h"
#include "metrics/fragment_cost.h"
#include "metrics/metrics.h"
#include "metrics/op_cost.h"
#include "output/result_store.h"
#include "output/row.h"
#include "relief/cell_projection_bend.h"
#include "relief/relief_map.h"
#include "run/cells.h"
#include "run/runner.h"
#include "scene/base_mesh.h"
#include "technique/technique.h"
#include "truth/make_truth.h"
#include "truth/truth_render.h"

namespace rl {

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
  std::unique_ptr<ShadowMapPass> shadow_map;  // scene_shadows' light view, if asked for
  std::unique_ptr<SceneTruth> truth;
  double build_ms = 0;
  double texel_world = 0;  // world size of a texel on the base
  // The texel errors are measured in: the truth's where it has its own resolution, so that
  // every texture resolution of a scene is judged by one yardstick.
  double metric_texel = 0;
  // The base's fitted curvature against its closed form (sphere, torus): Figure 5.28.
  std::optional<CurvatureFitError> curvature_fit;
  // A cell complex's edges projected onto its faces (Figure 3): measured once, copied to rows.
  std::optional<ProjectionBend> projection_bend;
  double ao_ms = 0;  // the texture-space AO map's precompute (ambient_occlusion)
  bool ao_from_cache = false;
  // Prepared technique instances by (technique, parameters): prepare() runs once per asset.
  std::map<std::string, std::pair<std::unique_ptr<Technique>, double>> prepared;
  // The GL programs building the asset drew with (a GPU-sampled cell complex, a fragment-shader
  // AO map), and each prepared instance's prepare(): part of every row drawn from them.
  std::map<std::string, ProgramDesc> programs;
  std::map<std::string, std::map<std::string, ProgramDesc>> prepared_programs;
};

// The truth of one (asset, viewport, view): its G-buffer and how it was traced.
struct TruthView {
  GBuffer g;
  TruthStats stats;
  GBuffer footprint;  // colour averaged over each pixel (footprint_samples > 1), else empty
};

// What one cell's technique drew and cost.
struct CellMeasure {
  GBuffer g;
  FragmentCost cost;
  OpCost ops;
  // The config's cost model's prediction of this frame (NaN without one) and the model's name.
  double model_frame_ms = std::numeric_limits<double>::quiet_NaN();
  std::string model_gpu;
  ImageMetrics m;
  FrameTiming timing;
  std::vector<std::pair<std::string, double>> frame_columns;
  double precompute_ms = 0;
  bool precompute_cached = false;
  size_t technique_bytes = 0;
  // Set when a fragment paid more fetches than the technique declares it can (contract.h).
  std::string fetch_bound_warning;
  // Every GL program the row depends on: its asset's, its prepare()'s and its frames'.
  std::map<std::string, ProgramDesc> programs;
};

// Where a cell's pictures and G-buffers go.
struct CellFiles {
  std::string image_dir, gbuffer_dir;
};

// A cell's technique parameters as "name=value ..." (its run log and G-buffer header name it).
std::string describe_params(const Cell& cell);
// The colour channels of a G-buffer, for a PNG.
std::vector<float> rgb_of(const GBuffer& g);

// Assets: the map, base, truth, texel sizes, AO map and GPU textures of one (scene, texture
// resolution); and the run log's line for them.
std::unique_ptr<Asset> build_asset(const SweepConfig& config, const SceneDesc& scene,
                                   const Cell& cell, bool progress);
std::string describe_asset(const SceneDesc& scene, const Asset& asset);

// Truth: one (asset, viewport, view) traced; its accuracy stated for the run log; its files.
TruthView trace_truth(const SweepConfig& config, const SceneDesc& scene, const Asset& asset,
                      const Cell& cell, const Camera& camera);
std::string describe_truth_bound(const GBuffer& truth, double texel_world);
CellFiles cell_files(const RunOptions& options, const SceneDesc& scene);
void write_truth_files(const SweepConfig& config, const CellFiles& files, const SceneDesc& scene,
                       const Cell& cell, const Camera& camera, const GBuffer& truth,
                       const GBuffer& footprint);

// Measure: what one cell's technique draws and costs, against its truth.
CellMeasure measure_cell(const SweepConfig& config, const SceneDesc& scene, Asset& asset,
                         const Cell& cell, const Camera& camera, const TruthView& truth,
                         bool software_gl);

// Write: every measured column of a cell's row beside its identity; its pictures and G-buffer.
Row cell_row(const Cell& cell, const SceneDesc& scene, const Camera& camera, const Asset& asset,
             const CellMeasure& c, const TruthView& truth, const std::string& renderer);
void write_cell_files(Row& row, const SweepConfig& config, const RunOptions& options,
                      const CellFiles& files, const SceneDesc& scene, const Cell& cell,
                      const Camera& camera, const GBuffer& g, const GBuffer& truth,
                      double metric_texel);

}  // namespace rl
