#include "run/cells.h"

#include <algorithm>
#include <set>

#include "config/config_technique.h"
#include "core/columns.h"
#include "core/hash.h"
#include "metrics/fragment_cost.h"
#include "metrics/metrics.h"
#include "technique/technique.h"

namespace rl {
namespace {

// The columns that name a cell (its parameters are declared by its technique), and those the
// runner measures itself: the view's spread, timing, precompute and memory, the run's labels.
const ColumnDeclaration cell_identity_columns(
    "run (cell identity)",
    {{"technique", "", "the technique's registry name", ColumnKind::Identity},
     {"scene", "", "the config's scene name", ColumnKind::Identity},
     {"elevation_deg", "degrees", "the view's elevation above the base", ColumnKind::Identity},
     {"azimuth_deg", "degrees", "the view's azimuth", ColumnKind::Identity},
     {"texture_res", "texels", "the relief map's resolution asked for", ColumnKind::Identity},
     {"viewport", "pixels", "the viewport, WxH", ColumnKind::Identity},
     {"bake_axis", "",
      "a three-view impostor's bake drawn for the view: the mesh axis it was baked along (x, y "
      "or z); the view's elevation and azimuth stay those of the scene's own 'up'",
      ColumnKind::Identity}});

const ColumnDeclaration runner_columns(
    "run (runner)",
    {ColumnSpec{"elev_min_deg", "degrees",
                "the smallest elevation of the view rays over covered pixels"}
         .neither_better(),
     ColumnSpec{"elev_max_deg", "degrees",
                "the largest elevation of the view rays over covered pixels"}
         .neither_better(),
     ColumnSpec{
         "frame_ms", "ms",
         "median frame time of the colour-only shader (timer queries on a GPU, glFinish + wall "
         "clock on llvmpipe)"}
         .reported(),
     ColumnSpec{"fps", "1/s", "frames per second, 1000 / frame_ms"}.higher_is_better(),
     ColumnSpec{"rays_per_s", "1/s",
                "viewport pixels x frames per second (Apaza & Andujar's count)"}
         .higher_is_better(),
     {"frame_ms_min", "ms", "the fastest timed frame"},
     {"frame_ms_iqr", "ms", "interquartile range of the timed frames"},
     ColumnSpec{"frames_timed", "frames", "frames the median is over"}.neither_better(),
     {"timing", "", "how frames were timed (timer query or glFinish + wall clock)",
      ColumnKind::Text},
     {"precompute_ms", "ms", "the technique's prepare() time (its precompute)"},
     {"precompute_cached", "",
      "the precompute came from the cache (precompute_ms is then the "
      "read)",
      ColumnKind::Flag},
     ColumnSpec{"memory_bytes", "bytes",
                "the relief's textures plus the technique's own (three times that for a "
                "three-view impostor's three bakes)"}
         .reported(),
     {"ao_precompute_ms", "ms", "time to compute the texture-space AO map"},
     {"ao_precompute_cached", "", "the AO map came from the cache", ColumnKind::Flag},
     ColumnSpec{"ao_rescale", "", "the AO map's rescale factor for the scene's depth"}
         .neither_better(),
     {"ao_drawn", "",
      "the technique drew the scene's AO (false: ambient_occlusion.render = false, the scene "
      "without AO scored against the AO truth)",
      ColumnKind::Flag},
     {"curvature_fit_err_mean_pct", "%",
      "the base's fitted vertex curvature (Listing 5.8) against its closed form, sphere and torus "
      "bases: per vertex the larger error of A and B over the larger exact coefficient, the mean "
      "over vertices"},
     {"curvature_fit_err_max_pct", "%", "the same, the largest over vertices"},
     {"curvature_sign_match_pct", "%",
      "of the base's exact curvature coefficients that are not planar, the share the fit gives "
      "the right sign (Figure 5.28's red and blue)"},
     {"effects", "", "the effects the scene asks for", ColumnKind::Text},
     {"texture_size", "texels", "the map's size as built, WxH", ColumnKind::Text},
     {"renderer", "", "the GL renderer the row was measured on", ColumnKind::Text},
     {"key", "", "the cell's key in the result store", ColumnKind::Text},
     {"setting", "", "the technique's parameters at this cell, every one named (name=value)",
      ColumnKind::Text},
     {"measured_from", "",
      "digests of everything the row was measured from beyond its key: inputs, truth_code, "
      "metrics_code, draw_code, technique_code, programs, renderer, cost_model "
      "(output/provenance.h); a run reuses a stored row only when every one is as it is now",
      ColumnKind::Text},
     {"image_render", "", "the render's PNG, relative to the run's folder", ColumnKind::Text},
     {"image_truth", "", "the truth's PNG", ColumnKind::Text},
     {"image_error", "", "the error heat map's PNG", ColumnKind::Text},
     {"gbuffer", "", "the render's G-buffer (OpenEXR), when exported", ColumnKind::Text},
     {"gbuffer_truth", "", "the truth's G-buffer (OpenEXR), when exported", ColumnKind::Text}});

}  // namespace

namespace {

// A part of every truth key since keys were first made, once bumped by hand when a metric or the
// truth was redefined (2: the exact heightfield truth and its bounds; 3: the bound along the
// surface's own normal; 4: the cost of every shaded fragment; 6: warp_fetches_per_px). Frozen:
// what a bump said is now derived, from the code's digests in every row's provenance
// (output/provenance.h), and the number stays only so that stored and committed rows keep
// their keys.
constexpr int kKeyFormat = 6;

}  // namespace

std::vector<std::string> parameter_columns(const SweepConfig& config) {
  std::vector<std::string> cols;
  for (const TechniqueSweep& ts : config.techniques)
    for (const ParamSpec& p : TechniqueRegistry::instance().find(ts.name)->info.params)
      if (std::find(cols.begin(), cols.end(), p.name) == cols.end()) cols.push_back(p.name);
  return cols;
}

namespace {

// The scene a view of scene `si` is drawn from, and the view in that scene's frame: for a
// three-view impostor, its bake along the axis nearest the view (scene/scene.h's
// nearest_bake_view); for any other scene, itself and the view as given.
struct DrawnView {
  size_t scene_index = 0;
  View view;
};

DrawnView drawn_view(const SweepConfig& config, size_t si, const View& view) {
  const SceneDesc& scene = config.scenes[si];
  if (!scene.relief.three_views) return {si, view};
  const AxisView nearest = nearest_bake_view(view, scene.relief.mesh_up);
  for (size_t i = 0; i < config.scenes.size(); ++i) {
    const SceneDesc& bake = config.scenes[i];
    const bool ours = i == si || bake.bake_of == scene.name;
    if (ours && bake.relief.mesh_up == nearest.up) return {i, nearest.view};
  }
  throw std::logic_error("scene '" + scene.name + "' has no bake along its nearest axis");
}

// The cell's keys, from what it draws: its asset (the drawn scene at its resolution), its
// truth (that asset, viewport and view) and the cell itself (truth, technique, parameters, run
// settings).
void key_cell(Cell& c, const SweepConfig& config, const SceneDesc& drawn,
              const TechniqueInfo& info) {
  const std::string scene_text = config.scene_canonical.at(drawn.name);
  c.asset_key = hex64(fnv1a64(scene_text + "|res=" + std::to_string(c.texture_res)));
  // A truth of a fixed resolution (truth_resolution) is one surface for every texture
  // resolution of the scene: traced once per view, shared by them all.
  const std::string truth_source =
      drawn.truth_texture_res > 0
          ? hex64(fnv1a64(scene_text + "|truth_res=" + std::to_string(drawn.truth_texture_res)))
          : c.asset_key;
  nlohmann::ordered_json truth_id = {{"asset", truth_source},
                                     {"w", c.width},
                                     {"h", c.height},
                                     {"el", c.view.elevation_deg},
                                     {"az", c.view.azimuth_deg},
                                     {"tol", config.truth_tolerance},
                                     {"v", kKeyFormat}};
  if (c.view.roll_deg != 0) truth_id["roll"] = c.view.roll_deg;  // absent: keys hold
  c.truth_key = hex64(fnv1a64(truth_id.dump()));
  ParamValues keyed = c.params;
  for (const ParamSpec& p : info.params)
    if (p.neutral_default && c.params.at(p.name) == p.default_value) keyed.erase(p.name);
  nlohmann::ordered_json id = {{"truth", c.truth_key},    {"technique", c.technique},
                               {"params", keyed},         {"frames", config.frames},
                               {"warmup", config.warmup}, {"images", config.write_images}};
  // Only when asked, so cells of sweeps without G-buffers keep their keys.
  if (config.write_gbuffers) id["gbuffers"] = true;
  // Its rows carry the footprint columns: a run without them is another cell.
  if (config.footprint_samples > 1) id["footprint"] = config.footprint_samples;
  // A shared truth no longer names the asset: the cell must.
  if (drawn.truth_texture_res > 0) id["asset"] = c.asset_key;
  c.key = hex64(fnv1a64(id.dump()));
}

}  // namespace

std::vector<Cell> expand_cells(const SweepConfig& config, size_t* duplicates) {
  std::vector<Cell> cells;
  std::set<std::string> keys;
  if (duplicates) *duplicates = 0;
  for (size_t si = 0; si < config.scenes.size(); ++si) {
    const SceneDesc& scene = config.scenes[si];
    if (!scene.bake_of.empty()) continue;  // drawn through its three-view scene's cells
    for (const TechniqueSweep& ts : config.techniques) {
      if (!ts.runs_on(scene.name)) continue;
      const TechniqueInfo& info = TechniqueRegistry::instance().find(ts.name)->info;
      const std::vector<ParamValues> settings = parameter_settings(ts);
      for (int tex : config.texture_res) {
        const int res = resolve_texture_res(scene, tex);
        for (const auto& [w, h] : config.viewports) {
          for (const View& asked : config.views) {
            const auto [drawn_index, view] = drawn_view(config, si, asked);
            const SceneDesc& drawn = config.scenes[drawn_index];
            for (const ParamValues& params : settings) {
              Cell c;
              c.scene_index = drawn_index;
              c.technique = ts.name;
              c.params = params;
              c.texture_res = res;
              c.width = w;
              c.height = h;
              c.view = view;
              key_cell(c, config, drawn, info);
              c.identity["technique"] = ts.name;
              c.identity["scene"] = scene.name;
              c.identity["elevation_deg"] = asked.elevation_deg;
              c.identity["azimuth_deg"] = asked.azimuth_deg;
              c.identity["texture_res"] = res;
              c.identity["viewport"] = std::to_string(w) + "x" + std::to_string(h);
              if (scene.relief.three_views)
                c.identity["bake_axis"] = std::string(1, char('x' + drawn.relief.mesh_up));
              for (const ParamSpec& p : info.params) c.identity[p.name] = params.at(p.name);
              if (!keys.insert(c.key).second) {
                if (duplicates) ++*duplicates;
                continue;
              }
              cells.push_back(std::move(c));
            }
          }
        }
      }
    }
  }
  return cells;
}

}  // namespace rl
