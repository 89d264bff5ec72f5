// What the truth of a relief on a curved base costs and how far it states it can be off: for
// every scene on a curved base in the given sweep configs, the truth is built as a sweep builds
// it (the base mesh, the truth's own map), then rendered at each elevation (the configs' first
// azimuth and viewport), or at each of the configs' own views; per row the share of covered pixels
// whose stated bound (G-buffer aux.w, a world distance) is at most 0.05 texel, the largest bound,
// and the build and trace times. Not part of CI: the closing notes' before/after tables of the
// curved-base truth come from it.
//
//   curved_truth [--elevations 5,20,45,90 | --config-views] CONFIG...
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "config/config.h"
#include "core/elapsed.h"
#include "metrics/metrics.h"
#include "relief/meta_relief.h"
#include "scene/base_mesh.h"
#include "scene/relief_asset.h"
#include "truth/make_truth.h"

namespace rl {
namespace {

std::vector<double> split_numbers(const std::string& s) {
  std::vector<double> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::stod(item));
  return out;
}

struct Totals {
  double build_ms = 0, trace_ms = 0;
  long covered = 0, trusted = 0;
};

// One scene of `config`: its truth built once, then traced at every elevation.
void study_scene(const SweepConfig& config, const SceneDesc& scene,
                 const std::vector<double>& elevations, Totals& totals) {
  const int res =
      resolve_texture_res(scene, config.texture_res.empty() ? 0 : config.texture_res[0]);
  const int truth_res = scene.truth_texture_res > 0 ? scene.truth_texture_res : res;
  const ReliefMap map = build_relief_asset(scene, truth_res);
  const BaseMesh mesh = make_base_mesh(scene.base, scene.size, scene.tile);
  const auto start = std::chrono::steady_clock::now();
  const SceneTruth truth(scene, map, config.truth_tolerance, &mesh);
  const double build_ms = ms_since(start);
  const ReliefMap& layer0 = map.meta ? map.meta->layers()[0].map : map;
  const double texel = texel_world(mesh, MapSize{layer0.width, layer0.height});
  const auto [width, height] = config.viewports.empty() ? std::pair{512, 512} : config.viewports[0];
  const double azimuth = config.views.empty() ? 30.0 : config.views[0].azimuth_deg;
  std::vector<View> views;
  for (double elevation : elevations) views.push_back(View{elevation, azimuth});
  if (elevations.empty()) views = config.views;
  totals.build_ms += build_ms;
  for (const View& view : views) {
    const double elevation = view.elevation_deg;
    const Camera camera = make_camera(scene, view, width, height);
    TruthStats stats;
    const GBuffer g = truth.render(map, scene, camera, scene.effects, &stats);
    const TruthBoundStats bound = truth_bound_stats(g, texel);
    const long trusted = bound.covered - bound.uncertain;
    std::printf("| %s | %s | %s | %dx%d | %.0f | %.0f | %.0f | %ld | %.3f%% | %.3g |\n",
                config.name.c_str(), scene.name.c_str(), scene.base.kind.c_str(), layer0.width,
                layer0.height, elevation, build_ms, stats.trace_ms, bound.covered,
                100.0 * double(trusted) / double(std::max<long>(1, bound.covered)),
                bound.largest_texels);
    std::fflush(stdout);
    totals.trace_ms += stats.trace_ms;
    totals.covered += bound.covered;
    totals.trusted += trusted;
  }
}

}  // namespace
}  // namespace rl

int main(int argc, char** argv) {
  using namespace rl;
  std::vector<double> elevations = {5, 20, 45, 90};
  std::vector<std::string> configs;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--elevations" && a + 1 < argc)
      elevations = split_numbers(argv[++a]);
    else if (arg == "--config-views")
      elevations.clear();
    else
      configs.push_back(arg);
  }
  if (configs.empty()) {
    std::fprintf(stderr,
                 "usage: curved_truth [--elevations 5,20,45,90 | --config-views] CONFIG...\n");
    return 2;
  }
  std::printf(
      "| config | scene | base | map | elevation | build ms | trace ms | covered px | bound <= "
      "0.05 texel | largest bound (texels) |\n|---|---|---|---|---|---|---|---|---|---|\n");
  Totals totals;
  for (const std::string& path : configs) {
    const SweepConfig config = load_sweep_config(path);
    for (const SceneDesc& scene : config.scenes)
      if (scene.base.curved()) study_scene(config, scene, elevations, totals);
  }
  std::printf("\ntotal: build %.0f ms, trace %.0f ms, %ld covered px, %.3f%% within 0.05 texel\n",
              totals.build_ms, totals.trace_ms, totals.covered,
              100.0 * double(totals.trusted) / double(std::max<long>(1, totals.covered)));
  return 0;
}
