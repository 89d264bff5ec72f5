// Safety-radius precompute (relief_robust), all cores, no disk cache: the faithful radii of
// Section 3.5 (blocked rays ignored, the default) and the conservative ones, at 256^2 and
// 1024^2, on procedural maps and on the rock-wall height map (resampled bilinearly).
// The paper reports about 10 s for 128^2 on its 2006 GPU (Baboud & Decoret, Section 3.5).
// Cone maps (cone_relaxed), relaxed and conservative, at 256^2, 512^2 and 1024^2.
// Texture-space AO maps (ambient_occlusion; Limberger et al. Section IV-A, 50 directions) at
// 256^2, 512^2 and 1024^2 for a relief 0.08 deep on a unit quad (height in texels = 0.08 x
// size): the line sweep (the default), the per-texel march and its fragment-shader version.
#include <benchmark/benchmark.h>

#include <cstring>

#include "../techniques/cone_relaxed/cone_map.h"
#include "../techniques/relief_robust/safety_radius.h"
#include "gl/context.h"
#include "gpu/gpu_ao_map.h"
#include "relief/ao_map.h"
#include "relief/image_io.h"
#include "relief/procedural.h"
#include "relief/relief_map.h"

namespace rl {
namespace {

ReliefMap rock(int size) {
  // The Irrlicht rock wall's 256^2 height map, resampled to size^2 (GL_LINEAR, repeat).
  static const ReliefMap source = [] {
    ReliefImageSource src;
    src.depth_path =
        std::string(RELIEFLAB_SOURCE_DIR) + "/assets/relief/rockwall/rockwall_height.bmp";
    return load_relief_images(src, 10.0);
  }();
  ReliefMap m;
  m.width = m.height = size;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double d = source.sample_depth((x + 0.5) / size, (y + 0.5) / size);
      m.relief.push_back(glm::vec4(0.5f, 0.5f, 1.0f, float(d)));
      m.color.push_back(glm::vec4(1));
    }
  return m;
}

// An 8-bit map of `kind` ("rock" or a procedural kind) at size^2.
ReliefMap bench_map(const std::string& kind, int size) {
  ReliefMap map = kind == "rock" ? rock(size) : make_procedural(kind, size, {}, 10.0, "bench");
  quantize_8bit(map);
  return map;
}

// FNV-1a of a map's bits: "the same map" at a glance when a change is meant to keep it.
template <typename T>
double fingerprint(const std::vector<T>& values) {
  uint32_t f = 2166136261u;
  for (const T& v : values) {
    uint32_t bits = 0;
    std::memcpy(&bits, &v, sizeof v);
    f = (f ^ bits) * 16777619u;
  }
  return double(f);
}

// Map sizes 256, 512 and 1024, one timed run each (a precompute takes seconds).
void at_map_sizes(benchmark::internal::Benchmark* b) {
  b->Arg(256)->Arg(512)->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
}

void BM_SafetyRadius(benchmark::State& state, std::string kind, bool ignore_blocked) {
  const ReliefMap map = bench_map(kind, int(state.range(0)));
  SafetyRadiusOptions o;
  o.ignore_blocked = ignore_blocked;
  SafetyRadii r;
  for (auto _ : state) {
    r = compute_safety_radii(map, o);
    benchmark::DoNotOptimize(r.radius.data());
  }
  double mean = 0;
  for (uint8_t v : r.radius) mean += v;
  state.counters["mean_radius"] = mean / r.radius.size();
  state.counters["zero_pct"] = 100.0 * r.zero_count() / r.radius.size();
  state.counters["starts_alone"] = double(r.starts_answered_alone);
  state.counters["fingerprint"] = fingerprint(r.radius);
}

#define RL_RADIUS_BENCH(name, kind, ignore) \
  BENCHMARK_CAPTURE(BM_SafetyRadius, name, kind, ignore)->Apply(at_map_sizes)
RL_RADIUS_BENCH(rock, "rock", true);
RL_RADIUS_BENCH(sines, "sines", true);
RL_RADIUS_BENCH(bricks, "bricks", true);
RL_RADIUS_BENCH(pyramids, "pyramids", true);
RL_RADIUS_BENCH(rock_conservative, "rock", false);
RL_RADIUS_BENCH(bricks_conservative, "bricks", false);

void BM_ConeMap(benchmark::State& state, std::string kind, bool relaxed) {
  const ReliefMap map = bench_map(kind, int(state.range(0)));
  ConeMapOptions o;
  o.relaxed = relaxed;
  ConeMap c;
  for (auto _ : state) {
    c = compute_cone_map(map, o);
    benchmark::DoNotOptimize(c.ratio.data());
  }
  double mean = 0;
  for (float v : c.ratio) mean += v;
  state.counters["mean_ratio"] = mean / c.ratio.size();
  state.counters["fingerprint"] = fingerprint(c.ratio);
}

#define RL_CONE_BENCH(name, kind, relaxed) \
  BENCHMARK_CAPTURE(BM_ConeMap, name, kind, relaxed)->Apply(at_map_sizes)
RL_CONE_BENCH(cone_rock, "rock", true);
RL_CONE_BENCH(cone_bricks, "bricks", true);
RL_CONE_BENCH(cone_pyramids, "pyramids", true);
RL_CONE_BENCH(cone_domes, "domes", true);
RL_CONE_BENCH(cone_rock_conservative, "rock", false);
RL_CONE_BENCH(cone_pyramids_conservative, "pyramids", false);

// The AO map by the line sweep (the default: relief/horizon_sweep.h), by the per-texel march on
// all cores (the paper's search), or (gpu) by the march in a fragment shader
// (harness/glsl/ao_map.frag): on llvmpipe that is the CPU again, JIT-compiled and vectorised;
// with a GPU, the GPU. The march and the shader give the same map; the sweep's stays within
// AoMap.SweepStaysCloseToThePerTexelMarch's bounds of it (compare mean_visibility).
enum class AoMethod { Sweep, March, Shader };

void BM_AoMap(benchmark::State& state, std::string kind, AoMethod method) {
  const int size = int(state.range(0));
  const ReliefMap map = bench_map(kind, size);
  AoMapOptions o;
  o.height_texels = 0.08 * size;
  if (method == AoMethod::Shader) {
    compute_ao_map_gpu(bench_map(kind, 16), o);      // compile first
    state.SetLabel(GlContext::shared().renderer());  // whose fragment shader it timed
  }
  AoMap a;
  for (auto _ : state) {
    a = method == AoMethod::Sweep   ? compute_ao_map(map, o)
        : method == AoMethod::March ? compute_ao_map_march(map, o)
                                    : compute_ao_map_gpu(map, o);
    benchmark::DoNotOptimize(a.visibility.data());
  }
  double mean = 0;
  for (float v : a.visibility) mean += v;
  state.counters["mean_visibility"] = mean / a.visibility.size();
  state.counters["fingerprint"] = fingerprint(a.visibility);
}

#define RL_AO_BENCH(name, kind, method) \
  BENCHMARK_CAPTURE(BM_AoMap, name, kind, AoMethod::method)->Apply(at_map_sizes)
RL_AO_BENCH(ao_rock, "rock", Sweep);
RL_AO_BENCH(ao_bricks, "bricks", Sweep);
RL_AO_BENCH(ao_sines, "sines", Sweep);
RL_AO_BENCH(ao_march_rock, "rock", March);
RL_AO_BENCH(ao_march_bricks, "bricks", March);
RL_AO_BENCH(ao_march_sines, "sines", March);
RL_AO_BENCH(ao_gpu_rock, "rock", Shader);
RL_AO_BENCH(ao_gpu_bricks, "bricks", Shader);
RL_AO_BENCH(ao_gpu_sines, "sines", Shader);

}  // namespace
}  // namespace rl

BENCHMARK_MAIN();
