#include "sweep/cells.h"

#include <algorithm>
#include <set>

#include "core/hash.h"
#include "metrics/fragment_cost.h"
#include "metrics/metrics.h"
#include "sweep/config_technique.h"
#include "technique/technique.h"

namespace rl {
namespace {

// Results change when the harness's measuring changes: bump this when a metric or the truth
// is redefined, so stale rows are not mistaken for current ones.
// 2: the exact heightfield truth and its bounds; 3: the bound along the surface's own normal;
// 4: the cost of every shaded fragment (metrics/fragment_cost.h), cone maps safe under
// filtering, depth slicing without slack on float maps; 6: warp_fetches_per_px, the default
// Pareto cost (a stored row without it would drop out of the fronts).
constexpr int kMeasurementVersion = 6;

}  // namespace

const std::vector<std::string>& measured_columns() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    ImageMetrics every;  // with the columns only some scenes measure (ambient occlusion)
    every.has_ao = true;
    for (const auto& [name, value] : every.named()) n.push_back(name);
    for (const auto& [name, value] : FragmentCost{}.named()) n.push_back(name);
    for (const char* c : {"elev_min_deg",
                          "elev_max_deg",
                          "frame_ms",
                          "fps",
                          "rays_per_s",
                          "frame_ms_min",
                          "frame_ms_iqr",
                          "frames_timed",
                          "precompute_ms",
                          "memory_bytes",
                          "truth_bound",
                          "truth_flagged",
                          "truth_subdivision",
                          "truth_ms",
                          "truth_unresolved_px",
                          "layers",
                          "layer_overflow_pct",
                          "layer_odd_pct",
                          "depth_complexity",
                          "ao_precompute_ms",
                          "ao_rescale",
                          "truth_ao_rays",
                          "cell_grid",
                          "mesh_faces",
                          "grey_cells",
                          "domain_faces",
                          "cell_bytes",
                          "cell_classify_ms",
                          "cell_sample_ms",
                          "cell_construction_ms",
                          "cell_distance_bytes",
                          "cell_ambiguous_regions",
                          "occluded_fragment_pct",
                          "multi_crossing_pct",
                          "intersections_per_s",
                          "slice_passes",
                          "fragments_per_pixel",
                          "fragments_max",
                          "face_count",
                          "base_passes"})
      n.push_back(c);
    return n;
  }();
  return names;
}

std::vector<std::string> parameter_columns(const SweepConfig& config) {
  std::vector<std::string> cols;
  for (const TechniqueSweep& ts : config.techniques)
    for (const ParamSpec& p : TechniqueRegistry::instance().find(ts.name)->info.params)
      if (std::find(cols.begin(), cols.end(), p.name) == cols.end()) cols.push_back(p.name);
  return cols;
}

std::vector<Cell> expand_cells(const SweepConfig& config, size_t* duplicates) {
  std::vector<Cell> cells;
  std::set<std::string> keys;
  if (duplicates) *duplicates = 0;
  for (size_t si = 0; si < config.scenes.size(); ++si) {
    const SceneDesc& scene = config.scenes[si];
    for (const TechniqueSweep& ts : config.techniques) {
      if (!ts.scenes.empty() &&
          std::find(ts.scenes.begin(), ts.scenes.end(), scene.name) == ts.scenes.end())
        continue;
      const TechniqueInfo& info = TechniqueRegistry::instance().find(ts.name)->info;
      const std::vector<ParamValues> settings = parameter_settings(ts);
      for (int tex : config.texture_res) {
        const int res = resolve_texture_res(scene, tex);
        for (const auto& [w, h] : config.viewports) {
          for (const View& view : config.views) {
            for (const ParamValues& params : settings) {
              Cell c;
              c.scene_index = si;
              c.technique = ts.name;
              c.params = params;
              c.texture_res = res;
              c.width = w;
              c.height = h;
              c.view = view;
              const std::string scene_text = config.scene_canonical.at(scene.name);
              c.asset_key = hex64(fnv1a64(scene_text + "|res=" + std::to_string(res)));
              // A truth of a fixed resolution (truth_resolution) is one surface for every
              // texture resolution of the scene: traced once per view, shared by them all.
              const std::string truth_source =
                  scene.truth_texture_res > 0
                      ? hex64(fnv1a64(scene_text +
                                      "|truth_res=" + std::to_string(scene.truth_texture_res)))
                      : c.asset_key;
              nlohmann::ordered_json truth_id = {{"asset", truth_source},
                                                 {"w", w},
                                                 {"h", h},
                                                 {"el", view.elevation_deg},
                                                 {"az", view.azimuth_deg},
                                                 {"tol", config.truth_tolerance},
                                                 {"v", kMeasurementVersion}};
              c.truth_key = hex64(fnv1a64(truth_id.dump()));
              nlohmann::ordered_json id = {
                  {"truth", c.truth_key},    {"technique", ts.name},
                  {"params", params},        {"frames", config.frames},
                  {"warmup", config.warmup}, {"images", config.write_images}};
              // Only when asked, so cells of sweeps without G-buffers keep their keys.
              if (config.write_gbuffers) id["gbuffers"] = true;
              // A shared truth no longer names the asset: the cell must.
              if (scene.truth_texture_res > 0) id["asset"] = c.asset_key;
              c.key = hex64(fnv1a64(id.dump()));
              c.identity["technique"] = ts.name;
              c.identity["scene"] = scene.name;
              c.identity["elevation_deg"] = view.elevation_deg;
              c.identity["azimuth_deg"] = view.azimuth_deg;
              c.identity["texture_res"] = res;
              c.identity["viewport"] = std::to_string(w) + "x" + std::to_string(h);
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
