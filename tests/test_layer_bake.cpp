// Non-height-field relief (Policarpo & Oliveira 2006), its data: the layer bake on meshes with
// known crossings, the 8-bit normals' cost and the procedural patterns' closedness and
// orientation. The multilayer search itself: techniques/multilayer/test_multilayer.cpp; scenes
// against the mesh: tests/test_multilayer_scenes.cpp.
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/triangle_mesh.h"
#include "gl/context.h"
#include "gpu/gpu_scene.h"
#include "relief/layer_bake.h"
#include "relief/pattern_mesh.h"
#include "scene/base_mesh.h"
#include "scene/relief_asset.h"
#include "support/test_support.h"
#include "truth/layers_truth.h"
#include "truth/pattern_base_truth.h"

namespace rl {
namespace {

TEST(LayerBake, AFloatingSlabHasTwoExactLayersFacingOut) {
  for (bool flip : {false, true}) {
    SCOPED_TRACE(flip ? "wound inward" : "wound outward");
    const ReliefMap map = bake_layers(test::layer_boxes({{0.25, 0.75, 0.3, 0.6}}, flip),
                                      pattern_frame(), 16, 16, 4, {1, 1, 1});
    const LayerStack& L = map.layers;
    const size_t texels = 256;
    ASSERT_EQ(L.count, 4);
    EXPECT_EQ(L.max_crossings, 2);
    EXPECT_EQ(L.overflow_texels, 0);
    EXPECT_EQ(L.misoriented_crossings, flip ? 2 * 8 * 8 : 0);
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) {
        const size_t i = size_t(y) * 16 + x;
        const bool inside = x >= 4 && x < 12 && y >= 4 && y < 12;
        ASSERT_EQ(L.used(i), inside ? 2 : 0) << x << "," << y;
        EXPECT_EQ(map.relief[i].a, inside ? L.depth[i] : 1.0f);
        if (!inside) continue;
        EXPECT_NEAR(L.depth[i], 0.3, 1e-5);
        EXPECT_NEAR(L.depth[texels + i], 0.6, 1e-5);
        EXPECT_EQ(L.depth[2 * texels + i], 1.0f);         // unused: the paper's 1.0
        EXPECT_NEAR(L.normal[i].z, 1.0, 1e-6);            // top: out of the solid, up
        EXPECT_NEAR(L.normal[texels + i].z, -1.0, 1e-6);  // bottom: down
      }
  }
}

// Section 7: a surface with a boundary bounds no solid; it is kept as two layers, entered and
// left, `open_surface_gap` apart. Beside it a closed slab keeps its two crossings as they are.
TEST(LayerBake, AnOpenSurfaceBecomesTwoLayersAndAClosedOneStaysAsItIs) {
  TriangleMesh mesh = test::layer_boxes({{0.25, 0.75, 0.6, 0.8}});  // closed, under the sheet
  const uint32_t first = uint32_t(mesh.positions.size());
  for (glm::vec2 c : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)})
    mesh.positions.push_back({c.x, c.y, -0.3f});  // a flat open sheet at depth 0.3
  mesh.triangles.push_back({first, first + 1, first + 2});
  mesh.triangles.push_back({first, first + 2, first + 3});
  const size_t texels = 256, slab = size_t(8) * 16 + 8, sheet_only = 0;
  for (double gap : {0.0, 0.05}) {
    SCOPED_TRACE(gap);
    const ReliefMap map = bake_layers(mesh, pattern_frame(), 16, 16, 4, {1, 1, 1}, false, gap);
    const LayerStack& L = map.layers;
    EXPECT_EQ(L.odd_texels, 0);
    ASSERT_EQ(L.used(sheet_only), 2);
    EXPECT_NEAR(L.depth[sheet_only], 0.3, 1e-5);
    EXPECT_NEAR(L.depth[texels + sheet_only], 0.3 + gap, 1e-5);
    EXPECT_NEAR(L.normal[sheet_only].z, 1.0, 1e-6);            // entered from above
    EXPECT_NEAR(L.normal[texels + sheet_only].z, -1.0, 1e-6);  // left at once, facing down
    ASSERT_EQ(L.used(slab), 4);  // the sheet's two, then the slab's own two
    EXPECT_NEAR(L.depth[2 * texels + slab], 0.6, 1e-5);
    EXPECT_NEAR(L.depth[3 * texels + slab], 0.8, 1e-5);
  }
  // Without it the sheet is one crossing per texel: odd, and dropped where close_open asks.
  const ReliefMap single = bake_layers(mesh, pattern_frame(), 16, 16, 4, {1, 1, 1}, true);
  EXPECT_EQ(single.layers.odd_texels, 256);
  EXPECT_EQ(single.layers.used(sheet_only), 0);
}

TEST(LayerBake, CrossingsBeyondTheLayersAreCountedAndTheTopOnesKept) {
  // Three stacked slabs: depth complexity 6 (the 8-layer case).
  const TriangleMesh stack =
      test::layer_boxes({{0.25, 0.75, 0.1, 0.2}, {0.25, 0.75, 0.4, 0.5}, {0.25, 0.75, 0.7, 0.8}});
  const ReliefMap four = bake_layers(stack, pattern_frame(), 8, 8, 4, {1, 1, 1});
  const ReliefMap eight = bake_layers(stack, pattern_frame(), 8, 8, 8, {1, 1, 1});
  EXPECT_EQ(four.layers.max_crossings, 6);
  EXPECT_EQ(four.layers.overflow_texels, 4 * 4);
  EXPECT_EQ(eight.layers.overflow_texels, 0);
  const size_t centre = 4 * 8 + 4;
  EXPECT_EQ(four.layers.used(centre), 4);
  EXPECT_EQ(eight.layers.used(centre), 6);
  EXPECT_NEAR(four.layers.depth[3 * 64 + centre], 0.5, 1e-5);  // the 4th crossing is kept
  EXPECT_NEAR(eight.layers.depth[5 * 64 + centre], 0.8, 1e-5);
}

// Figure 5 stores a layer's normal as x and y in 8 bits and rebuilds z on the layer's side;
// quantize_8bit does the same and says what it cost. Three texels of two layers: an up normal,
// one leaning 36.9 degrees on the back layer, and one 2.56 degrees off the base plane, whose x
// rounds to 1 and leaves z = 0 (the worst case of the representation: z is ill-conditioned near
// the plane); a texel with no surface on a layer does not count. 0 is not among the stored
// values (0.5 x 255 = 127.5 rounds to 128, 0.0039 after decoding), so even an up normal leans
// 0.32 degrees.
TEST(LayerStorage, QuantizingReportsTheAngleThe8BitNormalsCost) {
  ReliefMap m;
  m.width = 3;
  m.height = 1;
  m.relief.assign(3, glm::vec4(0.5f, 0.5f, 1.0f, 0.0f));
  m.color.assign(3, glm::vec4(1.0f));
  LayerStack& l = m.layers;
  l.count = 2;
  l.depth = {0.2f, 0.3f, 0.4f, 0.6f, 0.7f, 1.0f};
  const double off_plane = std::sin(2.56 * M_PI / 180);
  l.normal = {{0, 0, 1},
              {0.6f, 0, 0.8f},
              {float(std::sqrt(1 - off_plane * off_plane)), 0, float(off_plane)},
              {0, 0, -1},
              {0.6f, 0, -0.8f},
              {1, 0, 0}};
  l.color.assign(6, glm::vec3(1.0f));
  quantize_8bit(m);
  EXPECT_NEAR(l.normal_storage_err_max_deg, 2.56, 0.01);
  // The other four: each component moves by at most 1 / 255 (at most 0.33 degrees here).
  EXPECT_GT(l.normal_storage_err_mean_deg, (2.56 + 4 * 0.1) / 5);
  EXPECT_LT(l.normal_storage_err_mean_deg, (2.56 + 4 * 0.33) / 5);
  EXPECT_EQ(l.normal[2].x, 1.0f);
  EXPECT_EQ(l.normal[2].z, 0.0f);
  EXPECT_NEAR(l.normal[0].x, 1.0 / 255, 1e-6);  // 0 stored as 128 / 255
}

TEST(PatternMesh, TilesCloseUpAndAreWoundOutward) {
  for (const char* kind : {"weave", "helix"}) {
    SCOPED_TRACE(kind);
    const TriangleMesh mesh = make_pattern_mesh(kind, {}, "test");
    // Every directed edge has its opposite once, with positions compared modulo the tile:
    // the tubes' open ends on the tile border meet the next tile's.
    auto key = [&](uint32_t v) {
      const glm::dvec3 p(mesh.positions[v]);
      auto wrap = [](double x) { return long(std::lround((x - std::floor(x + 1e-6)) * 1e5)); };
      return std::make_tuple(wrap(p.x), wrap(p.y), long(std::lround(p.z * 1e5)));
    };
    std::map<std::pair<decltype(key(0)), decltype(key(0))>, int> edges;
    for (const glm::uvec3& t : mesh.triangles)
      for (int k = 0; k < 3; ++k) ++edges[{key(t[k]), key(t[(k + 1) % 3])}];
    long unmatched = 0;
    for (const auto& [e, n] : edges) unmatched += n != 1 || edges.count({e.second, e.first}) != 1;
    EXPECT_EQ(unmatched, 0);
    const ReliefMap map =
        bake_layers(with_neighbour_tiles(mesh), pattern_frame(), 64, 64, 4, {1, 1, 1});
    EXPECT_EQ(map.layers.misoriented_crossings, 0);
    EXPECT_EQ(map.layers.odd_texels, 0);  // closed across the tiles
    EXPECT_EQ(map.layers.overflow_texels, 0);
    EXPECT_EQ(map.layers.max_crossings, 4);
  }
  EXPECT_THROW(make_pattern_mesh("weave", {{"amplitude", 0.05}}, "test"), ConfigError);
  EXPECT_THROW(make_pattern_mesh("helix", {{"radius", 0.4}}, "test"), ConfigError);
  EXPECT_THROW(make_pattern_mesh("weave", {{"knots", 1}}, "test"), ConfigError);
}

}  // namespace
}  // namespace rl
