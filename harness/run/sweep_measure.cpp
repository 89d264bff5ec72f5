#include "run/sweep_stages.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "core/elapsed.h"
#include "gl/render_target.h"

namespace rl {
namespace {

using Clock = std::chrono::steady_clock;

// The technique instance of a cell, prepared once per asset and parameter setting.
std::pair<std::unique_ptr<Technique>, double>& prepared_technique(const SweepConfig& config,
                                                                  const SceneDesc& scene,
                                                                  Asset& asset, const Cell& cell) {
  auto& slot = asset.prepared[cell.technique + "|" + describe_params(cell)];
  if (!slot.first) {
    slot.first = TechniqueRegistry::instance().create(cell.technique, cell.params, config.source);
    const auto t0 = Clock::now();
    slot.first->prepare_scene(scene, asset.map);
    glFinish();
    slot.second = ms_since(t0);
  }
  return slot;
}

}  // namespace

std::string describe_params(const Cell& c) {
  std::string s;
  for (const auto& [k, v] : c.params) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s=%g", k.c_str(), v);
    s += (s.empty() ? "" : " ") + std::string(buf);
  }
  return s;
}

CellMeasure measure_cell(const SweepConfig& config, const SceneDesc& scene, Asset& asset,
                         const Cell& cell, const Camera& camera, const GBuffer& truth,
                         bool software_gl) {
  auto& [technique, prepare_ms] = prepared_technique(config, scene, asset, cell);
  FrameInput frame{scene,
                   asset.map,
                   *asset.relief,
                   *asset.base,
                   camera,
                   scene.drawn_effects(),
                   asset.objects.get()};
  CellMeasure out;
  FragmentCounts counts;
  {
    RenderTarget target(cell.width, cell.height, RenderTarget::Kind::GBuffer);
    target.bind_and_clear();
    render_frame(*technique, frame, RenderTarget::Kind::GBuffer);
    target.read_back(out.g);
    target.read_back_costs(counts);
  }
  out.cost = fragment_cost(counts);
  out.frame_columns = technique->frame_columns();
  for (const auto& [name, value] : out.frame_columns) {
    const auto& declared = technique->info().columns;
    if (std::none_of(declared.begin(), declared.end(),
                     [&](const ColumnSpec& c) { return c.name == name; }))
      throw std::logic_error("technique '" + technique->info().name + "' wrote column '" + name +
                             "', which its describe() does not declare in .columns");
  }
  out.m = compare_gbuffers(out.g, truth, scene.depth, asset.metric_texel,
                           scene.effects.has(Effect::AmbientOcclusion));
  RenderTarget timing_target(cell.width, cell.height, RenderTarget::Kind::ColorOnly);
  out.timing = time_frames(
      [&] {
        timing_target.bind_and_clear();
        render_frame(*technique, frame, RenderTarget::Kind::ColorOnly);
      },
      config.warmup, config.frames, software_gl);
  out.precompute_ms = prepare_ms;
  out.precompute_cached = technique->prepared_from_cache();
  out.technique_bytes = technique->memory_bytes();
  return out;
}

}  // namespace rl
