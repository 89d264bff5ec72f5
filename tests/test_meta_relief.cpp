// Meta-relief texture mapping (Limberger, Schetinger & Oliveira, Section III): the combination
// of layers (Eqs. 1-2), its exact truth, its bake, its AO maps, and the shaders' per-fetch
// combination against all of them.
#include <cmath>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "config/config.h"
#include "gl/context.h"
#include "gl/shader_library.h"
#include "relief/heightfield_reference.h"
#include "relief/meta_relief.h"
#include "relief/procedural.h"
#include "run/cells.h"
#include "run/memory_estimate.h"
#include "scene/base_mesh.h"
#include "scene/relief_asset.h"
#include "support/test_support.h"
#include "technique/shader_technique.h"
#include "truth/meta_relief_truth.h"

namespace rl {
namespace {

ReliefMap layer_map(const std::string& kind, int resolution, double slope = 4.0) {
  return make_procedural(kind, resolution, {}, slope, "test");
}

// Layers whose texel-centre grids all coincide with a 32 x 32 map's (resolution x tiling = 32
// each), so the bake at 32 x 32 is exactly the combination (a sum of bilinears on one grid).
std::shared_ptr<const MetaRelief> aligned_meta() {
  return std::make_shared<const MetaRelief>(
      std::vector<MetaLayer>{{layer_map("sines", 32), 1.0, 1.0, 1.0},
                             {layer_map("pyramids", 16), 2.0, 0.5, 0.6},
                             {layer_map("bricks", 8), 4.0, 0.3, 0.3}});
}

// Fractional tilings (5.5 and 3.7: periods of 2 and 10 base tiles) on non-power-of-two maps.
std::shared_ptr<const MetaRelief> fractional_meta() {
  return std::make_shared<const MetaRelief>(
      std::vector<MetaLayer>{{layer_map("sines", 24), 1.0, 1.0, 1.0},
                             {layer_map("bricks", 20), 5.5, 0.3, 0.4},
                             {layer_map("pyramids", 12), 3.7, 0.2, 0.25}});
}

TEST(MetaRelief, RefusesWeightsSummingToZeroAndNonPositiveTilings) {
  const ReliefMap m = layer_map("sines", 8);
  auto make = [&](double tiling, double wn, double wd) {
    return MetaRelief({{m, 1.0, 0.0, 0.0}, {m, tiling, wn, wd}});
  };
  EXPECT_NO_THROW(make(2.5, 1, 1));
  EXPECT_THROW(make(2.5, 0, 1), std::invalid_argument);  // normal weights sum to 0
  EXPECT_THROW(make(2.5, 1, 0), std::invalid_argument);  // depth weights sum to 0
  EXPECT_THROW(make(0.0, 1, 1), std::invalid_argument);
  EXPECT_THROW(make(-2.0, 1, 1), std::invalid_argument);
  EXPECT_THROW(make(std::nan(""), 1, 1), std::invalid_argument);
  EXPECT_THROW(make(2.0, -1, 2), std::invalid_argument);  // Eqs. 1-2 take non-negative weights
}

TEST(MetaRelief, CombinesLikeEquationsOneAndTwo) {
  const auto meta = fractional_meta();
  const double u = 0.3137, v = 0.7211;
  double depth = 0, wd = 0, wn = 0;
  glm::dvec3 n(0);
  for (const MetaLayer& l : meta->layers()) {
    depth += l.weight_depth * l.map.sample_depth(u * l.tiling, v * l.tiling);
    n += l.weight_normal * decode_normal(l.map.sample_relief(u * l.tiling, v * l.tiling));
    wd += l.weight_depth;
    wn += l.weight_normal;
  }
  EXPECT_NEAR(meta->depth(u, v), depth / wd, 1e-15);
  const glm::dvec3 expected = glm::normalize(n / wn);
  const glm::dvec3 got = decode_normal(meta->relief(u, v));
  EXPECT_NEAR(glm::length(got - expected), 0.0, 1e-12);
  // Depth bounds hold everywhere.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> any(-3, 3);
  for (int i = 0; i < 2000; ++i) {
    const double d = meta->depth(any(rng), any(rng));
    EXPECT_GE(d, meta->min_depth() - 1e-12);
    EXPECT_LE(d, meta->max_depth() + 1e-12);
  }
}

TEST(MetaReliefTruth, MatchesTheExactReferenceOfTheBakeWhereTheBakeIsExact) {
  const auto meta = aligned_meta();
  const ReliefMap bake = bake_meta_relief(*meta, 32, 32);
  const MetaReliefTruth truth(meta);
  int hits = 0;
  for (const auto& r : test::random_tangent_rays(3000, 2, 89, 0.3, 11, 0.0)) {
    const ReferenceHit ref = intersect_heightfield(bake, r.origin, r.direction, 2.0);
    const double t = truth.first_hit(r.origin, r.direction, 0.0, 2.0);
    ASSERT_EQ(ref.hit, !std::isnan(t));
    if (!ref.hit) continue;
    ++hits;
    // The bake stores the combination in float: its depths differ by float rounding (~6e-8).
    EXPECT_NEAR(t, ref.t, 1e-5) << r.origin.x << " " << r.origin.y;
  }
  EXPECT_EQ(hits, 3000);
}

TEST(MetaReliefTruth, FractionalTilingHitsLieOnTheSurfaceWithNoEarlierCrossing) {
  const auto meta = fractional_meta();
  const MetaReliefTruth truth(meta);
  long cells = 0;
  for (const auto& r : test::random_tangent_rays(300, 3, 85, 0.25, 5, 0.0)) {
    const double t = truth.first_hit(r.origin, r.direction, 0.0, 2.0, &cells);
    ASSERT_FALSE(std::isnan(t));  // every downward ray meets a heightfield by depth 1
    const glm::dvec3 p = r.origin + r.direction * t;
    EXPECT_NEAR(meta->depth(p.x, p.y), p.z, 1e-9);
    // Dense sampling before the hit, 16 samples per finest texel crossed: the ray stays above.
    const double lateral = std::hypot(r.direction.x, r.direction.y) * meta->finest_texels();
    const int steps = int(std::ceil(16 * (lateral + 1) * t)) + 1;
    for (int k = 0; k < steps; ++k) {
      const double tk = t * k / steps;
      const glm::dvec3 q = r.origin + r.direction * tk;
      ASSERT_LT(q.z, meta->depth(q.x, q.y) + 1e-9) << "earlier crossing at t = " << tk;
    }
  }
  EXPECT_GT(cells, 300);  // the walk visits union cells of every layer
}

TEST(MetaRelief, AoOfLayersCombinesByProductAndMinimum) {
  const auto meta = aligned_meta();
  std::vector<std::vector<float>> flat, varied;
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> any(0.2f, 1.0f);
  for (const MetaLayer& l : meta->layers()) {
    flat.emplace_back(size_t(l.map.width) * l.map.height, 1.0f);
    std::vector<float> v(size_t(l.map.width) * l.map.height);
    for (float& x : v) x = any(rng);
    varied.push_back(v);
  }
  for (AoCombine how : {AoCombine::Product, AoCombine::Min})
    for (float a : combine_ao_maps(*meta, flat, 32, 32, how)) ASSERT_EQ(a, 1.0f);
  const auto product = combine_ao_maps(*meta, varied, 32, 32, AoCombine::Product);
  const auto minimum = combine_ao_maps(*meta, varied, 32, 32, AoCombine::Min);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      // Texel centres of the 32 x 32 map are every layer's texel centres: no interpolation.
      double p = 1, m = 1;
      for (size_t i = 0; i < meta->layers().size(); ++i) {
        const ReliefMap& lm = meta->layers()[i].map;
        // Layer texel x of the base's 32 is texel x mod its width (it repeats 32 / width times).
        const double a = varied[i][size_t(y % lm.height) * lm.width + x % lm.width];
        p *= a;
        m = std::min(m, a);
      }
      ASSERT_NEAR(product[y * 32 + x], p, 1e-6);
      ASSERT_NEAR(minimum[y * 32 + x], m, 1e-6);
      ASSERT_LE(product[y * 32 + x], minimum[y * 32 + x] + 1e-6);
    }
}

// A planar scene of sines with one more layer on top, combined at run time.
SceneDesc meta_scene(const std::string& layer_kind, int layer_res, double tiling, double weight) {
  SceneDesc s = test::procedural_scene("sines", 48, 0.08);
  MetaLayerDesc layer;
  layer.relief.procedural = layer_kind;
  layer.relief.native = {layer_res, layer_res};
  layer.tiling = tiling;
  layer.weight_normal = layer.weight_depth = weight;
  s.meta.layers.push_back(layer);
  return s;
}

TEST(MetaReliefRender, TwinLayersCombinedAtRunTimeRenderTheSingleMapWithTwiceTheFetches) {
  // Two equal layers with equal weights are the map itself (0.5 d + 0.5 d = d exactly), so the
  // runtime combination must take the same search path, read each layer once per fetch, and
  // draw the same image.
  SceneDesc plain = test::procedural_scene("sines", 48, 0.08);
  SceneDesc twin = meta_scene("sines", 48, 1.0, 1.0);
  const View view{35, 30};
  const ParamValues params{{"linear_steps", 16}, {"binary_steps", 5}};
  const test::Measured a = test::measure(plain, "relief", params, view, 64);
  const test::Measured b = test::measure(twin, "relief", params, view, 64);
  int covered = 0;
  for (size_t i = 0; i < a.technique.color.size(); ++i) {
    ASSERT_EQ(a.technique.covered(i), b.technique.covered(i));
    if (!a.technique.covered(i)) continue;
    ++covered;
    // The normal is renormalised after the weighted sum: float rounding of the unit vector.
    EXPECT_NEAR(glm::length(a.technique.color[i] - b.technique.color[i]), 0.0, 1e-5);
    // fetches: the search's and the normal's double, the colour's (one) does not.
    const float fa = a.technique.hit[i].w, fb = b.technique.hit[i].w;
    EXPECT_EQ(fb, 2 * (fa - 1) + 1) << "pixel " << i;
  }
  EXPECT_GT(covered, 1000);
  // The truths are the same surface: one exact walk, one Embree tessellation.
  EXPECT_LT(b.metrics.at("wrong_pct"), a.metrics.at("wrong_pct") + 0.5);
}

TEST(MetaReliefRender, EveryRuntimeTechniqueCombinesFractionalTilingsFinitely) {
  for (const std::string& name : TechniqueRegistry::instance().names()) {
    const TechniqueInfo& info = TechniqueRegistry::instance().find(name)->info;
    if (!info.draws.reads.has(Representation::MetaRuntime)) continue;
    SCOPED_TRACE(name);
    SceneDesc s = meta_scene("bricks", 20, 5.5, 0.3);
    if (info.effects.has(Effect::AmbientOcclusion)) s.effects.add(Effect::AmbientOcclusion);
    s.ao.samples = 16;
    for (double elevation : {80.0, 12.0}) {
      const test::Measured m = test::measure(s, name, {}, View{elevation, 30}, 48);
      int covered = 0, truth_covered = 0;
      for (size_t i = 0; i < m.technique.color.size(); ++i) {
        truth_covered += m.truth.covered(i);
        if (!m.technique.covered(i)) continue;
        ++covered;
        for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(m.technique.color[i][c]));
        // Each fetch of the relief reads both layers: at least the hit normal's two.
        ASSERT_GE(m.technique.hit[i].w, 2.0f);
      }
      // The base is drawn whole: every pixel the truth covers is shaded (a search may differ).
      EXPECT_GE(covered, truth_covered * 9 / 10);
      EXPECT_GT(truth_covered, 200);
      EXPECT_TRUE(std::isfinite(m.metrics.at("wrong_pct")));
    }
  }
}

TEST(MetaReliefRender, RuntimeAoIsTheLayersAoCombinedAtTheHitPastTheFirstTile) {
  // Three base tiles: a 5.5 tiling does not repeat with the base, so a map of the combination
  // over one tile would seam at u = 1 and 2; the per-fetch combination must not.
  for (auto how : {MetaReliefDesc::AoCombine::Product, MetaReliefDesc::AoCombine::Min}) {
    SceneDesc s = meta_scene("bricks", 20, 5.5, 0.3);
    s.tile = 3;
    s.effects.add(Effect::AmbientOcclusion);
    s.ao.samples = 4;
    s.meta.ao_combine = how;
    const test::Measured m =
        test::measure(s, "relief", {{"linear_steps", 16}, {"binary_steps", 5}}, View{45, 30}, 64);
    ReliefMap map = build_relief_asset(s, 48);
    attach_ao_map(map, s, texel_world(s, 48));
    ASSERT_EQ(map.meta_ambient_visibility.size(), 2u);
    const AoCombine cpu =
        how == MetaReliefDesc::AoCombine::Min ? AoCombine::Min : AoCombine::Product;
    int checked = 0, past_first_tile = 0;
    for (size_t i = 0; i < m.technique.size(); ++i) {
      if (!m.technique.covered(i)) continue;
      const glm::dvec2 uv(m.technique.hit[i].x, m.technique.hit[i].y);
      const double expected = combined_ao(*map.meta, map.meta_ambient_visibility, uv.x, uv.y, cpu);
      // GL_LINEAR weights are 8-bit fractions on llvmpipe.
      ASSERT_NEAR(m.technique.aux[i].x, expected, 4e-3) << "uv " << uv.x << ", " << uv.y;
      ++checked;
      past_first_tile += uv.x > 1.0 || uv.y > 1.0;
    }
    EXPECT_GT(checked, 1000);
    EXPECT_GT(past_first_tile, 500);
  }
}

TEST(MetaReliefRender, ScenesWithoutMetaReliefCompileNoLayerCombination) {
  GlContext::shared();
  for (const std::string& name : TechniqueRegistry::instance().names()) {
    auto t = TechniqueRegistry::instance().create(name, {}, "test");
    auto* shader = dynamic_cast<const ShaderTechnique*>(t.get());
    if (!shader || !t->info().draws.reads.has(Representation::MetaRuntime)) continue;
    SurfaceVariant meta;
    meta.meta_layers = 3;
    const auto target = RenderTarget::Kind::GBuffer;
    const GLuint plain = ShaderLibrary::shared().program(shader->surface_program({}, target));
    const GLuint combined =
        ShaderLibrary::shared().program(shader->surface_program({}, target, meta));
    EXPECT_EQ(glGetUniformLocation(plain, "rl_meta_tiling"), -1) << name;
    EXPECT_NE(glGetUniformLocation(combined, "rl_meta_tiling"), -1) << name;
    if (!t->info().effects.has(Effect::AmbientOcclusion)) continue;
    // With AO, the layers' maps per fetch (product or minimum), not the combined map.
    for (auto how : {MetaReliefDesc::AoCombine::Product, MetaReliefDesc::AoCombine::Min}) {
      meta.meta_ao = how;
      const GLuint ao = ShaderLibrary::shared().program(
          shader->surface_program({Effect::AmbientOcclusion}, target, meta));
      EXPECT_NE(glGetUniformLocation(ao, "rl_meta_ao"), -1) << name;
      EXPECT_EQ(glGetUniformLocation(ao, "rl_ao"), -1) << name;
    }
    meta.meta_ao = MetaReliefDesc::AoCombine::Bake;
    const GLuint baked_ao = ShaderLibrary::shared().program(
        shader->surface_program({Effect::AmbientOcclusion}, target, meta));
    EXPECT_NE(glGetUniformLocation(baked_ao, "rl_ao"), -1) << name;
  }
}

TEST(MetaReliefSweep, ATruthResolutionSharesTheTruthAcrossTextureResolutionsNotTheCells) {
  const std::string text = R"(
[sweep]
name = "t"
elevations = [30, 60]
viewports = [16]
texture_res = [16, 32, 64]
[[scene]]
name = "meta"
relief = { procedural = "sines", resolution = 64 }
truth_resolution = 64
[scene.meta_relief]
[[scene.meta_relief.layers]]
relief = { procedural = "bricks", resolution = 32 }
tiling = 2.5
[[technique]]
name = "relief"
)";
  const std::vector<Cell> cells = expand_cells(parse_sweep_config(text, "t.toml", "."));
  std::set<std::string> keys, truths, assets;
  for (const Cell& c : cells) {
    keys.insert(c.key);
    truths.insert(c.truth_key);
    assets.insert(c.asset_key);
  }
  EXPECT_EQ(cells.size(), 6u);  // 3 resolutions x 2 views: none dropped as a repeat
  EXPECT_EQ(keys.size(), 6u);
  EXPECT_EQ(assets.size(), 3u);
  EXPECT_EQ(truths.size(), 2u);  // one truth per view, whatever the resolution
}

// Three 8192^2 layers grew a run past 6 GB while the memory estimate counted layer 0 only: the
// estimate counts every layer at its own size (and the bake where the scene bakes).
TEST(MetaReliefSweep, TheMemoryEstimateCountsEveryLayer) {
  auto estimate = [](const std::string& meta) {
    const std::string text = R"(
[sweep]
name = "t"
elevations = [45]
viewports = [16]
[[technique]]
name = "relief"
[[scene]]
name = "meta"
relief = { procedural = "sines", resolution = 64 }
)" + meta;
    const SweepConfig config = parse_sweep_config(text, "t.toml", ".");
    return estimate_cell_memory(config, expand_cells(config).front()).bytes;
  };
  const std::string layer =
      "[[scene.meta_relief.layers]]\nrelief = { procedural = \"bricks\", "
      "resolution = 8192 }\n";
  const double none = estimate("");
  const double three = estimate("[scene.meta_relief]\n" + layer + layer + layer);
  EXPECT_GE(three - none, 3 * 8192.0 * 8192.0 * 30);  // at least 30 bytes a texel (as measured)
  // A bake of the combination at 4096 adds its own map.
  const double runtime = estimate("[scene.meta_relief]\n" + layer);
  const double baked =
      estimate("[scene.meta_relief]\ncombine = \"baked\"\nbake_resolution = 4096\n" + layer);
  EXPECT_GE(baked - runtime, 4096.0 * 4096.0 * 30);
}

// Layers scale with layer 0 (texture_res): 7 layers of 2048 at texture_res 8192 over a 2048 map
// are built at 8192 each, and estimated so (they passed at their declared size and then climbed
// past 6 GB).
TEST(MetaReliefSweep, TheMemoryEstimateCountsLayersAtTheirScaledSize) {
  std::string text = R"(
[sweep]
name = "t"
elevations = [45]
viewports = [16]
texture_res = [8192]
[[technique]]
name = "relief"
[[scene]]
name = "meta"
relief = { procedural = "sines", resolution = 2048 }
)";
  for (int i = 0; i < 7; ++i)
    text +=
        "[[scene.meta_relief.layers]]\nrelief = { procedural = \"bricks\", resolution = 2048 }\n";
  const SweepConfig config = parse_sweep_config(text, "t.toml", ".");
  const double bytes = estimate_cell_memory(config, expand_cells(config).front()).bytes;
  EXPECT_GE(bytes, 7 * 8192.0 * 8192.0 * 30);
}

}  // namespace
}  // namespace rl
