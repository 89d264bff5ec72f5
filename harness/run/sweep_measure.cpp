#include "run/sweep_stages.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "core/elapsed.h"
#include "core/error.h"
#include "gl/op_count_buffer.h"
#include "gl/render_target.h"
#include "relief/meta_relief.h"

namespace rl {
namespace {

using Clock = std::chrono::steady_clock;

// The key of a cell's prepared technique instance (and its prepare()'s programs) in its asset.
std::string prepared_key(const Cell& cell) {
  return cell.technique + "|" + describe_params(cell);
}

// The technique instance of a cell, prepared once per asset and parameter setting.
std::pair<std::unique_ptr<Technique>, double>& prepared_technique(const SweepConfig& config,
                                                                  const SceneDesc& scene,
                                                                  Asset& asset, const Cell& cell) {
  const std::string key = prepared_key(cell);
  auto& slot = asset.prepared[key];
  if (!slot.first) {
    const ProgramUses uses;
    slot.first = TechniqueRegistry::instance().create(cell.technique, cell.params, config.source);
    const auto t0 = Clock::now();
    slot.first->prepare_scene(scene, asset.map);
    glFinish();
    slot.second = ms_since(t0);
    asset.prepared_programs[key] = uses.programs();
  }
  return slot;
}

// What each fragment of the frame executes, by kind: the timed (colour-only) programs drawn once
// in their op-counting form (gl/op_counting.h).
// A shader the op-counting compilers cannot take (glslang reads GLSL more strictly than some
// drivers) leaves the row's op columns and model_frame_ms empty, with a warning once per
// technique, rather than failing the run: the contract holds the built-in techniques to it.
OpCost count_ops(Technique& technique, const FrameInput& frame, int width, int height,
                 int group_stride) {
  OpCountBuffer ops(width, height);
  RenderTarget target(width, height, RenderTarget::Kind::ColorOnly);
  OpCost shadow_map_cost = OpCost::none();
  PixelOpCounts counts;
  try {
    OpCountingScope counting(group_stride);
    // The shadow map's pass first, into counts of its own size: the GPU pays for it too. (With
    // op_count_stride > 1 the map then holds only the counted groups' depth, so the counted
    // scene fragments may see more light than the timed frame's: the lookup's ops do not depend
    // on what it reads; only the shading's choice of its lit or shadowed colour does, a few
    // float ops.)
    if (frame.shadow_map) {
      const int size = frame.shadow_map->size();
      OpCountBuffer shadow_ops(size, size);
      shadow_ops.bind();
      render_shadow_map(technique, frame);
      PixelOpCounts shadow_counts = shadow_ops.read_back();
      shadow_counts.group_stride = group_stride;
      shadow_map_cost = op_cost(shadow_counts);
    }
    target.bind_and_clear();
    ops.bind();
    render_scene(technique, frame, RenderTarget::Kind::ColorOnly);
    counts = ops.read_back();
  } catch (const GlError& e) {
    static std::set<std::string> warned;
    if (warned.insert(technique.info().name).second)
      std::fprintf(stderr, "relieflab: warning: no op counts (and no model_frame_ms) for %s: %s\n",
                   technique.info().name.c_str(), e.what());
    return OpCost::none();
  }
  counts.group_stride = group_stride;
  if (!frame.shadow_map) return op_cost(counts);
  const double size = frame.shadow_map->size();
  return with_pass(op_cost(counts), shadow_map_cost, size * size / (double(width) * height));
}

// The op counts of a cell's frame and its cost model's prediction. They feed the model only: a
// sweep that asks for none (cost_model = "none") draws no op-counting frame.
void add_model_cost(const SweepConfig& config, Technique& technique, const FrameInput& frame,
                    const Cell& cell, CellMeasure& out) {
  out.ops = OpCost::none();
  if (!config.cost_model) return;
  out.ops = count_ops(technique, frame, cell.width, cell.height, config.op_count_stride);
  out.model_frame_ms = predict_frame_ms(
      *config.cost_model,
      {double(cell.width) * cell.height, out.cost.fragments, out.ops.warp_ops_per_px});
  if (std::isfinite(out.model_frame_ms)) out.model_gpu = config.cost_model->name;
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

namespace {

// A promise is checked on every cell a sweep measures, not only by the contract suite: a
// plugin whose fragments fetch more than its describe() declares is named in the run log.
// A describe() counts samples of the map; a meta-relief combined per fetch reads every layer's
// texture for each (`textures_per_sample`).
std::string check_fetch_bound(const TechniqueInfo& info, const Cell& cell, const ReliefMap& map,
                              int textures_per_sample, const FragmentCost& cost) {
  const double bound =
      textures_per_sample * info.contract.max_fetches(whole_frame_query(cell.params, map));
  if (!(cost.frag_fetches_max > bound)) return "";  // within it, or not counted (NaN)
  char line[160];
  std::snprintf(line, sizeof line, "a fragment paid %.0f fetches, over the %.0f",
                cost.frag_fetches_max, bound);
  return "relieflab: warning: " + info.name + " " + describe_params(cell) + ": " + line +
         " its describe() declares (" + info.contract.max_fetches_formula +
         "): its contract does not hold on this cell";
}

}  // namespace

CellMeasure measure_cell(const SweepConfig& config, const SceneDesc& scene, Asset& asset,
                         const Cell& cell, const Camera& camera, const TruthView& truth,
                         bool software_gl) {
  const ProgramUses uses;
  auto& [technique, prepare_ms] = prepared_technique(config, scene, asset, cell);
  FrameInput frame{scene,
                   asset.map,
                   *asset.relief,
                   *asset.base,
                   camera,
                   scene.drawn_effects(),
                   asset.objects.get(),
                   asset.shadow_map.get()};
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
  // The bound is a plain render's: shadow rays and AO samples fetch on top of it.
  if (!frame.effects.has(Effect::SelfShadow) && !frame.effects.has(Effect::AmbientOcclusion))
    out.fetch_bound_warning = check_fetch_bound(
        TechniqueRegistry::instance().find(cell.technique)->info, cell, asset.map,
        scene.meta.runtime() && asset.map.meta ? int(asset.map.meta->layers().size()) : 1,
        out.cost);
  add_model_cost(config, *technique, frame, cell, out);
  out.frame_columns = technique->frame_columns();
  for (const auto& [name, value] : out.frame_columns) {
    const auto& declared = technique->info().columns;
    if (std::none_of(declared.begin(), declared.end(),
                     [&](const ColumnSpec& c) { return c.name == name; }))
      throw std::logic_error("technique '" + technique->info().name + "' wrote column '" + name +
                             "', which its describe() does not declare in .columns");
  }
  out.m =
      measure_metrics({.technique = out.g,
                       .truth = truth.g,
                       .depth_world = scene.depth,
                       .texel_world = asset.metric_texel,
                       .ambient_occlusion = scene.effects.has(Effect::AmbientOcclusion),
                       .scene_shadows = scene.effects.has(Effect::SceneShadows),
                       .footprint = truth.footprint.color.empty() ? nullptr : &truth.footprint});
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
  out.programs = uses.programs();
  out.programs.insert(asset.programs.begin(), asset.programs.end());
  const auto& prepared = asset.prepared_programs[prepared_key(cell)];
  out.programs.insert(prepared.begin(), prepared.end());
  return out;
}

}  // namespace rl
