#pragma once
// Sweep configs (TOML). A config names scenes, techniques with parameter lists, views,
// viewports and texture resolutions; the harness runs their product. Everything is checked
// here, before any work: unknown keys, unknown techniques, bad values, missing files and
// effects a technique cannot simulate are ConfigErrors naming the file, line and key.
#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "config/scene_input.h"
#include "core/cost_model.h"
#include "core/params.h"
#include "scene/scene.h"

namespace rl {

// A [[plot]] of a config: error against cost per group of rows, with the Pareto front
// (output/pareto.h draws it).
struct PlotSpec {
  // Cost (lower is better): by default time on a GPU -- measured where the row ran on one,
  // else the cost model's prediction from the run's op counts (gpu_frame_ms, core/cost_model.h),
  // every pass of a multi-pass technique included; any row column may be chosen (the counts,
  // warp_fetches_per_px, stay selectable).
  std::string x = "gpu_frame_ms";
  std::string y = "wrong_pct";  // error (lower is better): the headline error
  std::vector<std::string> group = {"scene", "elevation_deg"};
  bool log_y = true;
};

// A [[technique]] of a config. Its settings are the Cartesian product of the parameter lists
// (a parameter not listed takes its default), times the `sets` when given: each set pairs
// values of several parameters (e.g. min/max samples) and is combined with every product
// setting; a parameter is listed or in sets, not both (config/config_technique.h).
struct TechniqueSweep {
  std::string name;
  std::vector<std::string> scenes;                         // empty = every scene
  std::map<std::string, std::vector<double>> param_lists;  // declared parameters only
  std::vector<ParamValues> sets;                           // paired settings, or none
  std::string where;                                       // "file:line" for messages
  bool runs_on(const std::string& scene) const {
    return scenes.empty() || std::find(scenes.begin(), scenes.end(), scene) != scenes.end();
  }
};

struct TableSpec {
  std::string file = "table.md";
  std::string title;
  std::vector<std::string> rows, columns, values;
  // How rows that share a table cell combine: "" (the first is shown and the table says how
  // many were hidden), "mean" or "max" of each value over them (e.g. over scenes and azimuths).
  std::string aggregate;
  // "markdown" (default) or "latex" (booktabs, best value per column in bold).
  std::string format = "markdown";
};

struct SweepConfig {
  std::string name = "sweep";
  std::string source;  // the config file, or "<built-in default>"
  std::vector<SceneDesc> scenes;
  std::vector<TechniqueSweep> techniques;
  std::vector<View> views;
  std::vector<std::pair<int, int>> viewports;
  std::vector<int> texture_res;  // 0 = the asset's native resolution
  int frames = 5;                // timed frames per cell (median reported)
  int warmup = 1;
  double heat_map_scale = 4;      // texels at the top of the heat map's colour scale
  double truth_tolerance = 2e-3;  // stated tessellation tolerance, depth units
  // Truth rays per pixel side for the footprint colour (psnr_footprint_db, ssim_footprint): what
  // a pixel shows when it averages everything under it, the reference for filtering and
  // mip-mapping. 1: off (the point-sampled truth alone).
  int footprint_samples = 1;
  bool write_images = true;
  bool write_gbuffers = false;  // raw G-buffers as OpenEXR (output/gbuffer_export.h)
  // The GPU whose frame time each row predicts (model_frame_ms): `[sweep] cost_model`, a model's
  // name or file, "none" for no prediction (config/cost_model_file.h).
  std::string cost_model_name;
  std::optional<CostModel> cost_model;
  // `[sweep] op_count_stride`: the op-counting render counts one 8 x 4 lockstep group in
  // stride^2 (gl/op_counting.h), a stratified sample that costs the sweep about that much less
  // time; 1 counts every group exactly.
  int op_count_stride = 2;
  std::vector<TableSpec> tables;
  std::vector<PlotSpec> plots;                         // Pareto plots of error against cost
  std::map<std::string, std::string> scene_canonical;  // per scene: text of what defines it
  // Per scene: every file it reads, in the role it is read in, with its content digest (the
  // rows' provenance names them: run/cell_provenance.h).
  std::map<std::string, std::vector<SceneInput>> scene_inputs;
  // Per scene: "file:line" of its [[scene]] table and of its relief = { ... }, so that an asset
  // that fails to load later is reported where the config asked for it.
  std::map<std::string, std::pair<std::string, std::string>> scene_sites;
  std::string canonical;  // canonical text of everything that affects results
  // The config's own text and the folder its relative paths resolve from: what a shard writes
  // down so that `relieflab merge` can rebuild the tables (run/shard.h).
  std::string text, base_dir;
};

// What a run writes into its output folder beside its tables (output/, run/): a [[table]]
// 'file' may not take one of these names, nor another table's.
const std::vector<std::string>& run_owned_names();

// Parses and validates a config file. Relative paths resolve against the config's folder,
// then the repository root.
SweepConfig load_sweep_config(const std::string& path);
// Parses config text (`source_name` is used in messages and to resolve relative paths).
SweepConfig parse_sweep_config(const std::string& text, const std::string& source_name,
                               const std::string& base_dir);
// The built-in default sweep (configs/default.toml, embedded at build time).
SweepConfig default_sweep_config();

// The resolution a texture_res entry means for a scene (0 = native).
int resolve_texture_res(const SceneDesc& scene, int texture_res);

}  // namespace rl
