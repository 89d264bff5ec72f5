// Technique frame time at 512x512 on a 45-degree view (median of timed frames: GL timer
// queries on a GPU, glFinish + wall clock on llvmpipe), with texture fetches per pixel.
#include <benchmark/benchmark.h>

#include "gl/context.h"
#include "gl/frame_timer.h"
#include "gl/render_target.h"
#include "metrics/metrics.h"
#include "scene/relief_asset.h"
#include "technique/technique.h"

namespace rl {
namespace {

void BM_Technique(benchmark::State& state, std::string technique, ParamValues params,
                  bool shadows) {
  GlContext& gl = GlContext::shared();
  SceneDesc scene;
  scene.name = "bricks";
  scene.relief.procedural = "bricks";
  scene.relief.native = {512, 512};
  if (shadows) scene.effects.add(Effect::SelfShadow);
  ReliefMap map = build_relief_asset(scene, 512);
  GpuRelief relief(map);
  GpuBase base(make_base_geometry(scene));
  const Camera cam = make_camera(scene, View{45, 30}, 512, 512);
  auto t = TechniqueRegistry::instance().create(technique, params, "bench");
  t->prepare_scene(scene, map);
  FrameInput frame{scene, map, relief, base, cam, scene.effects};
  // Fetches per covered pixel, from the G-buffer variant.
  GBuffer g;
  {
    RenderTarget target(512, 512, RenderTarget::Kind::GBuffer);
    target.bind_and_clear();
    t->render(frame, RenderTarget::Kind::GBuffer);
    target.read_back(g);
  }
  std::vector<double> fetches;
  for (size_t i = 0; i < g.size(); ++i)
    if (g.covered(i)) fetches.push_back(g.hit[i].w);
  RenderTarget target(512, 512, RenderTarget::Kind::ColorOnly);
  for (auto _ : state) {
    FrameTiming ft = time_frames(
        [&] {
          target.bind_and_clear();
          t->render(frame, RenderTarget::Kind::ColorOnly);
        },
        1, 9, gl.is_software());
    state.SetIterationTime(ft.median_ms / 1000.0);
  }
  state.counters["fetches_mean"] = error_stats(fetches).mean;
  state.SetLabel(gl.renderer());
}

BENCHMARK_CAPTURE(BM_Technique, normal, "normal", ParamValues{}, false)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Technique, parallax, "parallax", ParamValues{}, false)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Technique, relief_8, "relief", ParamValues{{"linear_steps", 8}}, false)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Technique, relief_32, "relief", ParamValues{{"linear_steps", 32}}, false)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Technique, relief_64, "relief", ParamValues{{"linear_steps", 64}}, false)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Technique, relief_32_shadow, "relief", ParamValues{{"linear_steps", 32}}, true)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace rl

BENCHMARK_MAIN();
