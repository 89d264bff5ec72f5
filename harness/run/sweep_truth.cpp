#include "run/sweep_stages.h"

#include <cstdio>

#include "output/gbuffer_export.h"
#include "relief/image_io.h"
#include "truth/ao_truth_cache.h"

namespace rl {

std::vector<float> rgb_of(const GBuffer& g) {
  std::vector<float> rgb(g.size() * 3);
  for (size_t i = 0; i < g.size(); ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = g.color[i][c];
  return rgb;
}

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

}  // namespace rl
