#include "run/sweep_stages.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <glm/glm.hpp>

#include "core/columns.h"
#include "output/gbuffer_export.h"
#include "relief/cell_complex.h"
#include "relief/heightfield_faces.h"
#include "relief/image_io.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

// Per projection type (Apaza & Andujar, Figure 2): its share of the domain-face texels, and the
// share of those whose line crosses the surface more than once -- where the type fails to make
// its cell's surface a height field and one distance per texel loses a sheet.
void add_projection_columns(Row& row, const CellComplex& cc, const ProjectionBend& bend) {
  std::array<double, 4> texels{}, multi{};
  const size_t per_face = size_t(cc.resolution()) * cc.resolution();
  for (size_t f = 0; f < cc.domain_faces().size(); ++f) {
    const auto type = size_t(cc.cells()[size_t(cc.domain_faces()[f].cell)].config.projection.type);
    texels[type] += double(per_face);
    for (size_t t = f * per_face; t < (f + 1) * per_face; ++t) multi[type] += cc.crossings()[t] > 1;
  }
  double all = 0;
  for (double n : texels) all += n;
  for (size_t type = 0; type < 4; ++type) {
    const std::string name =
        projection_type_name(CellProjection::Type(type));  // "perspective", "axial", ...
    row["texels_" + name + "_pct"] = all > 0 ? 100.0 * texels[type] / all : 0.0;
    row["multi_crossing_" + name + "_pct"] =
        texels[type] > 0 ? 100.0 * multi[type] / texels[type] : 0.0;
  }
  // Figure 3: how far mesh edges bend when projected onto their cell's faces.
  for (size_t type = 0; type < 4; ++type) {
    const std::string name = projection_type_name(CellProjection::Type(type));
    row["edge_pieces_" + name] = double(bend.pieces[type]);
    row["edge_bend_" + name + "_texels_max"] = bend.max_texels[type];
    row["edge_bend_" + name + "_texels_mean"] = bend.mean_texels[type];
  }
}

// A cell complex's construction (Apaza & Andujar, Table 1) and ray throughput (Table 2):
// intersections per second are the pixels the technique covers over the median frame time.
void add_cell_columns(Row& row, const CellComplex& cc, const ProjectionBend& bend, const GBuffer& g,
                      double frame_ms) {
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
  add_projection_columns(row, cc, bend);
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
  if (asset.map.cells)
    add_cell_columns(row, *asset.map.cells, *asset.projection_bend, c.g, c.timing.median_ms);
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

// What the truth of the cell's view says of itself: its front end, bound and trace, what an
// impostor's quad cannot show, and the reference AO.
void add_truth_columns(Row& row, const SceneDesc& scene, const Asset& asset, const CellMeasure& c,
                       const TruthView& truth) {
  row["truth_subdivision"] = asset.truth->subdivision();
  row["truth_bound"] = asset.truth->tessellation_bound();
  row["truth_flagged"] = c.m.truth_flagged();
  row["truth_ms"] = truth.stats.trace_ms;
  row["truth_unresolved_px"] = double(truth.stats.unresolved);
  if (scene.impostor()) {
    // The object's pixels the quad shows: covered, and not by a scene object (layer -1).
    long shown = 0;
    for (size_t i = 0; i < truth.g.size(); ++i)
      shown += truth.g.covered(i) && truth.g.hit[i].z >= 0 ? 1 : 0;
    const long object = shown + truth.stats.beyond_quad;
    row["beyond_quad_pct"] = object ? 100.0 * double(truth.stats.beyond_quad) / double(object) : 0;
  }
  if (scene.effects.has(Effect::AmbientOcclusion)) {
    row["ao_precompute_ms"] = asset.ao_ms;
    row["ao_precompute_cached"] = asset.ao_from_cache;
    row["ao_rescale"] = scene.ao.rescale(scene.depth);
    row["ao_drawn"] = scene.ao.render;
    row["truth_ao_rays"] = double(truth.stats.ao_rays);
  }
}

}  // namespace

// Every measured column of a cell's row, beside its identity.
Row cell_row(const Cell& cell, const SceneDesc& scene, const Camera& camera, const Asset& asset,
             const CellMeasure& c, const TruthView& truth, const std::string& renderer) {
  Row row = cell.identity;
  // An error column that measures nothing (no pixel covered) is empty, never zero.
  for (const auto& [name, value] : c.m.named()) row[name] = number_or_empty(value);
  add_elevation_columns(row, scene, camera, c.g, truth.g);
  add_timing_columns(row, cell, c.timing);
  row["precompute_ms"] = c.precompute_ms;
  row["precompute_cached"] = c.precompute_cached;
  for (const auto& [name, value] : c.cost.named()) row[name] = number_or_empty(value);
  for (const auto& [name, value] : c.ops.named()) row[name] = number_or_empty(value);
  row["model_frame_ms"] = number_or_empty(c.model_frame_ms);
  row["model_gpu"] = c.model_gpu;
  // Time on a GPU: measured where the row ran on one, else the cost model's.
  const bool on_gpu = c.timing.method == "gpu_timer";
  row["gpu_frame_ms"] = number_or_empty(on_gpu ? c.timing.min_ms : c.model_frame_ms);
  row["gpu_frame_ms_source"] =
      on_gpu ? "measured" : (c.model_gpu.empty() ? "" : "model " + c.model_gpu);
  for (const auto& [name, value] : c.frame_columns) row[name] = value;
  // A three-view impostor keeps its three bakes (one resolution and layer count) resident, and
  // what the technique builds from each.
  const int bakes = scene.relief.three_views ? 3 : 1;
  row["memory_bytes"] = double(bakes * (asset.relief->bytes() + c.technique_bytes));
  add_truth_columns(row, scene, asset, c, truth);
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
  row["setting"] = describe_params(cell);
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

}  // namespace rl
