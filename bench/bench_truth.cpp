// Truth throughput: rays/s of HeightfieldTruth::intersect (Embree on the lifted grid, then the
// exact walk) against raw rtcIntersect1 on the same Embree scene with the same rays,
// single-threaded, and the whole truth G-buffer (all cores), at 45 degrees and, on the TRaK5
// panel at 1024^2, at grazing views (the truth's build and trace separately, with the exact
// stage's work per ray); the displaced-mesh truth of a curved base: its build (the front end's
// sheet and its BVH) and its G-buffer. Not part of CI.
#include <cmath>
#include <map>
#include <memory>
#include <random>

#include <benchmark/benchmark.h>

#include "config/config.h"
#include "scene/base_mesh.h"
#include "scene/relief_asset.h"
#include "truth/displaced_truth.h"
#include "truth/heightfield_truth.h"
#include "truth/make_truth.h"
#include "truth/truth_render.h"

namespace rl {
namespace {

struct Setup {
  SceneDesc scene;
  ReliefMap map;
  std::unique_ptr<HeightfieldTruth> truth;
  std::vector<glm::dvec3> origins, directions;  // texture space, starting at the top
};

Setup& setup(const std::string& kind, int res) {
  static std::map<std::string, Setup> cache;
  const std::string key = kind + std::to_string(res);
  if (cache.count(key)) return cache[key];
  Setup& s = cache[key];
  s.scene.name = kind;
  s.scene.relief.procedural = kind;
  s.scene.relief.native = {res, res};
  s.map = build_relief_asset(s.scene, res);
  s.truth = std::make_unique<HeightfieldTruth>(s.map);
  // Rays at 45 degrees that stay inside the one tile the raw scene holds: origins in the
  // tile's middle, lateral travel at most 0.08 tile units over the full depth.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.2, 0.8), az(0, 6.2831853);
  for (int i = 0; i < 1 << 16; ++i) {
    const double a = az(rng);
    s.origins.push_back({u(rng), u(rng), -1e-6});
    s.directions.push_back({0.08 * std::cos(a), 0.08 * std::sin(a), 1.0});
  }
  return s;
}

void BM_TruthIntersect(benchmark::State& state, std::string kind) {
  Setup& s = setup(kind, int(state.range(0)));
  size_t i = 0;
  for (auto _ : state) {
    TruthHit h = s.truth->intersect(s.origins[i], s.directions[i], 0, 1.0 + 1e-6);
    benchmark::DoNotOptimize(h);
    i = (i + 1) % s.origins.size();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["subdivision"] = s.truth->subdivision();
}

void BM_RawEmbreeIntersect1(benchmark::State& state, std::string kind) {
  Setup& s = setup(kind, int(state.range(0)));
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  size_t i = 0;
  for (auto _ : state) {
    RTCRayHit rh{};
    rh.ray.org_x = float(s.origins[i].x);
    rh.ray.org_y = float(s.origins[i].y);
    rh.ray.org_z = float(s.origins[i].z);
    rh.ray.dir_x = float(s.directions[i].x);
    rh.ray.dir_y = float(s.directions[i].y);
    rh.ray.dir_z = float(s.directions[i].z);
    rh.ray.tnear = 0;
    rh.ray.tfar = 1.0f + 1e-6f;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(s.truth->scene(), &context, &rh);
    benchmark::DoNotOptimize(rh);
    i = (i + 1) % s.origins.size();
  }
  state.SetItemsProcessed(state.iterations());
}

// Renders the truth G-buffer once per iteration; rays traced, for items processed.
template <typename Truth>
uint64_t time_truth_gbuffers(benchmark::State& state, const Truth& truth, const ReliefMap& map,
                             const SceneDesc& scene, const Camera& cam) {
  uint64_t rays = 0;
  for (auto _ : state) {
    TruthStats stats;
    GBuffer g = render_truth(truth, map, scene, cam, EffectSet{}, &stats);
    benchmark::DoNotOptimize(g.color.data());
    rays += stats.primary_rays;
  }
  state.SetItemsProcessed(int64_t(rays));
  return rays;
}

void BM_TruthGBuffer(benchmark::State& state) {
  Setup& s = setup("bricks", 256);
  time_truth_gbuffers(state, *s.truth, s.map, s.scene,
                      make_camera(s.scene, View{45, 30}, 512, 512));
}

// The panel map at 1024^2 (upsampled from 512^2, normalised), filling a 512^2 viewport.
SceneDesc panel_scene() {
  SceneDesc scene;
  scene.name = "panel";
  scene.relief.normal_path =
      std::string(RELIEFLAB_SOURCE_DIR) + "/assets/relief/trak5/panel1_n.png";
  scene.relief.normalize = true;
  scene.relief.native = {512, 512};
  return scene;
}

void BM_TruthBuildPanel(benchmark::State& state) {
  const ReliefMap map = build_relief_asset(panel_scene(), int(state.range(0)));
  int k = 0;
  for (auto _ : state) {
    HeightfieldTruth truth(map);
    k = truth.subdivision();
  }
  state.counters["subdivision"] = k;
}

void BM_TruthGBufferPanel(benchmark::State& state) {
  SceneDesc scene = panel_scene();
  const double elevation = double(state.range(1));
  apply_fill_framing(scene, elevation, 1.0);
  const ReliefMap map = build_relief_asset(scene, int(state.range(0)));
  const HeightfieldTruth truth(map);
  const uint64_t queries0 = truth.embree_queries(), cells0 = truth.exact_cells();
  const uint64_t rays = time_truth_gbuffers(state, truth, map, scene,
                                            make_camera(scene, View{elevation, 30}, 512, 512));
  state.counters["embree_queries_per_ray"] =
      double(truth.embree_queries() - queries0) / double(std::max<uint64_t>(rays, 1));
  state.counters["exact_cells_per_ray"] =
      double(truth.exact_cells() - cells0) / double(std::max<uint64_t>(rays, 1));
}

// A curved base (chapter 5): `kind` on a 32-segment sphere at res^2 (two tiles around).
void BM_DisplacedTruthBuild(benchmark::State& state, std::string kind) {
  SceneDesc scene;
  scene.relief.procedural = kind;
  scene.base.kind = "sphere";
  const int res = int(state.range(0));
  const ReliefMap map = build_relief_asset(scene, res);
  const BaseMesh base = make_base_mesh(scene.base, scene.size, scene.tile);
  size_t triangles = 0;
  int subdivision = 0;
  for (auto _ : state) {
    DisplacedTruth truth(base, map, scene.depth);
    triangles = truth.triangles();
    subdivision = truth.subdivision();
  }
  state.counters["sheet_triangles"] = double(triangles);
  state.counters["sheet_subdivision"] = subdivision;
}

void BM_DisplacedTruthGBuffer(benchmark::State& state) {
  SceneDesc scene;
  scene.relief.procedural = "sines";
  scene.base.kind = "sphere";
  const ReliefMap map = build_relief_asset(scene, 256);
  const DisplacedTruth truth(make_base_mesh(scene.base, scene.size, scene.tile), map, scene.depth);
  const uint64_t rays =
      time_truth_gbuffers(state, truth, map, scene, make_camera(scene, View{30, 30}, 512, 512));
  // The two stages' work per ray: sheet entries found by Embree, chords solved against the map.
  state.counters["embree_queries_per_ray"] =
      double(truth.embree_queries()) / double(std::max<uint64_t>(rays, 1));
  state.counters["chords_per_ray"] = double(truth.chords()) / double(std::max<uint64_t>(rays, 1));
}

// The reference AO of the default sweep's AO scenes (the rock wall on Embree, and its
// meta-relief traced exactly) at 45 degrees: the hemisphere rays dominate the default sweep.
void BM_ReferenceAo(benchmark::State& state, std::string scene_name) {
  const SweepConfig config = default_sweep_config();
  SceneDesc scene;
  for (const SceneDesc& s : config.scenes)
    if (s.name == scene_name) scene = s;
  ReliefMap map = build_relief_asset(scene, scene.relief.native.longer());
  const SceneTruth truth(scene, map, config.truth_tolerance);
  const int side = int(state.range(0));
  const Camera cam = make_camera(scene, View{45, 30}, side, side);
  uint64_t rays = 0;
  double stderr_sum = 0, covered = 0;
  for (auto _ : state) {
    TruthStats stats;
    GBuffer g = truth.render(map, scene, cam, EffectSet{Effect::AmbientOcclusion}, &stats);
    rays += stats.ao_rays;
    for (size_t i = 0; i < g.aux.size(); ++i)
      if (g.covered(i)) {
        stderr_sum += g.aux[i].y;
        covered += 1;
      }
  }
  state.SetItemsProcessed(int64_t(rays));
  // The noise floor the sweep reports (ao_ref_stderr) and the rays it took per pixel.
  state.counters["stderr_mean"] = stderr_sum / std::max(covered, 1.0);
  state.counters["rays_per_pixel"] = double(rays) / std::max(covered, 1.0);
}

BENCHMARK_CAPTURE(BM_ReferenceAo, rockwall_ao, "rockwall_ao")
    ->Arg(64)
    ->Arg(256)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ReferenceAo, rockwall_meta, "rockwall_meta")
    ->Arg(64)
    ->Arg(256)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_TruthIntersect, bricks, "bricks")->Arg(256)->Arg(512);
BENCHMARK_CAPTURE(BM_RawEmbreeIntersect1, bricks, "bricks")->Arg(256)->Arg(512);
BENCHMARK_CAPTURE(BM_TruthIntersect, sines, "sines")->Arg(256)->Arg(512);
BENCHMARK_CAPTURE(BM_RawEmbreeIntersect1, sines, "sines")->Arg(256)->Arg(512);
BENCHMARK(BM_TruthGBuffer)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_DisplacedTruthBuild, sines, "sines")
    ->Arg(128)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_DisplacedTruthBuild, bricks, "bricks")
    ->Arg(128)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_DisplacedTruthGBuffer)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TruthBuildPanel)->Arg(1024)->Arg(2048)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TruthGBufferPanel)
    ->Args({1024, 1})
    ->Args({1024, 5})
    ->Args({1024, 20})
    ->Args({2048, 5})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace rl

BENCHMARK_MAIN();
