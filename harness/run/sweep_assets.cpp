#include "run/sweep_stages.h"

#include <chrono>
#include <cstdio>

#include "core/elapsed.h"
#include "gpu/cell_gpu_sampling.h"
#include "gpu/gpu_ao_map.h"
#include "relief/ao_map.h"
#include "relief/cell_complex.h"
#include "relief/meta_relief.h"
#include "scene/relief_asset.h"

namespace rl {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

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
  // A cell complex whose maps the scene has drawn on the GPU (cells sampling = "gpu").
  auto take_gpu_maps = [&](ReliefMap& map) {
    if (!map.cells || !scene.relief.cells.gpu_sampling) return;
    stage("sampling the cell complex's maps on the GPU");
    map.cells = std::make_shared<const CellComplex>(with_gpu_sampled_maps(*map.cells));
  };
  asset->map = build_relief_asset(scene, cell.texture_res);
  take_gpu_maps(asset->map);
  if (asset->map.cells) asset->projection_bend = projection_bend(*asset->map.cells);
  // The truth's own map where the scene gives it another depth resolution (truth_resolution)
  // or another colour map (truth_color_resolution).
  const int truth_res = scene.truth_texture_res > 0 ? scene.truth_texture_res : cell.texture_res;
  const int truth_color =
      scene.truth_color_texture_res > 0 ? scene.truth_color_texture_res : scene.color_texture_res;
  if (scene.relief.size_at(truth_res) != scene.relief.size_at(cell.texture_res) ||
      truth_color != scene.color_texture_res) {
    asset->truth_map =
        std::make_unique<ReliefMap>(build_relief_asset(scene, truth_res, truth_color));
    take_gpu_maps(*asset->truth_map);
  }
  asset->objects = std::make_unique<ObjectPass>(scene.objects);
  if (scene.effects.has(Effect::SceneShadows))
    asset->shadow_map = std::make_unique<ShadowMapPass>(scene);
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
    asset->base = std::make_unique<GpuBase>(make_base_geometry(scene, &asset->map));
    asset->truth =
        std::make_unique<SceneTruth>(scene, asset->truth_source(), config.truth_tolerance);
    asset->texel_world = texel_world(scene, cell.texture_res);
    asset->metric_texel = texel_world(
        scene, scene.truth_texture_res > 0 ? scene.truth_texture_res : cell.texture_res);
  }
  if (scene.drawn_effects().has(Effect::AmbientOcclusion))
    stage("computing the ambient occlusion map");
  const AoMap ao =
      attach_ao_map(asset->map, scene, asset->texel_world, ao_map_method(scene.ao.map_method));
  asset->ao_ms = ao.compute_ms;
  asset->ao_from_cache = ao.from_cache;
  asset->relief = std::make_unique<GpuRelief>(asset->map, scene.meta.runtime());
  asset->build_ms = ms_since(t0);
  return asset;
}

// The run log's line for a built asset: its size, build time and what its truth is.
std::string describe_asset(const SceneDesc& scene, const Asset& asset) {
  char buf[320];
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
  else if (scene.base.curved())
    std::snprintf(buf, sizeof buf,
                  "relieflab: asset %s at %dx%d: built in %.0f ms (truth %.0f ms, exact to "
                  "rounding on the curved base: %s; each trace states its bound in texels)",
                  scene.name.c_str(), layer0_size.width, layer0_size.height, asset.build_ms,
                  asset.truth->build_ms(),
                  scene.relief.layers > 0
                      ? "the pattern mesh placed on every base triangle"
                      : ("walked through the base's prisms behind a sheet of " +
                         std::to_string(asset.truth->subdivision()) + "x" +
                         std::to_string(asset.truth->subdivision()) + " per base triangle")
                            .c_str());
  else if (asset.truth->tessellation_bound() == 0)
    std::snprintf(buf, sizeof buf,
                  "relieflab: asset %s at %dx%d: built in %.0f ms (truth %.0f ms, exact to "
                  "rounding: each trace states its bound in texels)",
                  scene.name.c_str(), layer0_size.width, layer0_size.height, asset.build_ms,
                  asset.truth->build_ms());
  else
    std::snprintf(buf, sizeof buf,
                  "relieflab: asset %s at %dx%d: built in %.0f ms (Embree truth %.0f ms, "
                  "tessellation %dx%d per texel, deviation <= %.2g depth units)",
                  scene.name.c_str(), layer0_size.width, layer0_size.height, asset.build_ms,
                  asset.truth->build_ms(), asset.truth->subdivision(), asset.truth->subdivision(),
                  asset.truth->tessellation_bound());
  return buf;
}

}  // namespace rl
