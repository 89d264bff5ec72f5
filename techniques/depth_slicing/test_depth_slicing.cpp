// Multi-pass depth slicing (chapter 5, Listing 5.2) with exact expected values: a plateau on a
// slice, one slice, fragments counted per slice, slice planes met edge-on. On an object of
// heightfield faces: tests/test_heightfield_faces.cpp.
#include <map>

#include <gtest/gtest.h>

#include "gl/context.h"
#include "gpu/gpu_scene.h"
#include "relief/image_io.h"
#include "scene/relief_asset.h"
#include "support/test_support.h"

namespace rl {
namespace {

// A flat relief at depth 51/255 = 0.2 (exact in 8 bits) as an image scene, solid floor.
SceneDesc plateau_scene() {
  const std::string dir = test::scratch_dir("plateau");
  std::vector<float> px(16 * 16 * 3, 51.0f / 255.0f);
  write_png(dir + "/plateau.png", 16, 16, 3, px);
  SceneDesc s;
  s.name = "plateau";
  s.relief.depth_path = dir + "/plateau.png";
  s.relief.height_convention = false;
  s.relief.native = {16, 16};
  s.quantize = true;
  s.depth = 0.1;
  return s;
}

TEST(DepthSlicing, APlateauOnASliceStaysOnIt) {
  // Slices over a solid floor run from depth 0 to 1 inclusive: with 6 slices (0, 0.2, ... 1) a
  // plateau at 0.2 is found on its own slice, exactly; with 5 (0, 0.25, ...) on the next one;
  // one slice is the floor.
  GlContext::shared();
  const SceneDesc scene = plateau_scene();
  const ReliefMap map = build_relief_asset(scene, 16);
  ASSERT_FLOAT_EQ(map.relief[0].a, 0.2f);
  GpuRelief relief(map);
  std::vector<ProbeRay> rays;
  for (const test::TangentRay& r : test::random_tangent_rays(200, 5, 90, 0.1, 11, 0.0))
    rays.push_back({glm::vec3(r.origin), glm::vec3(r.direction)});
  for (const auto& [slices, depth] :
       std::vector<std::pair<int, float>>{{6, 0.2f}, {5, 0.25f}, {1, 1.0f}, {2, 1.0f}}) {
    SCOPED_TRACE(slices);
    for (bool view_aligned : {false}) {
      auto t = TechniqueRegistry::instance().create(
          "depth_slicing", {{"slices", slices}, {"view_aligned", double(view_aligned)}}, "test");
      for (const ProbeHit& h : t->probe(map, relief, rays, glm::dvec2(0.1))) {
        ASSERT_TRUE(h.hit);
        EXPECT_FLOAT_EQ(h.depth, depth);
      }
    }
  }
}

TEST(DepthSlicing, EveryFragmentOfEverySliceIsCounted) {
  // Straight down on the plateau with 6 slices, the centre pixel is covered by all six: six
  // fragments, each one depth fetch, and the five at or below 0.2 kept (one colour fetch each,
  // though the depth test then keeps only the nearest): 11 fetches, 6 passes.
  const SceneDesc scene = plateau_scene();
  const test::Measured m = test::measure(scene, "depth_slicing", {{"slices", 6}}, View{90, 0}, 64);
  const size_t centre = 32 * 64 + 32;
  ASSERT_TRUE(m.technique.covered(centre));
  EXPECT_EQ(m.technique.hit[centre].w, 11.0f);
  EXPECT_NEAR(m.technique.position[centre].z, -0.2 * scene.depth, 1e-6);
  EXPECT_LT(m.metrics.at("wrong_pct"), 0.5);
  auto t = TechniqueRegistry::instance().create("depth_slicing", {{"slices", 6}}, "test");
  GlContext::shared();
  ReliefMap map = build_relief_asset(scene, 16);
  GpuRelief relief(map);
  GpuBase base(make_base_geometry(scene));
  const Camera camera = make_camera(scene, View{90, 0}, 64, 64);
  FrameInput frame{scene, map, relief, base, camera, scene.effects, nullptr};
  RenderTarget target(64, 64, RenderTarget::Kind::GBuffer);
  target.bind_and_clear();
  render_frame(*t, frame, RenderTarget::Kind::GBuffer);
  std::map<std::string, double> columns;
  for (const auto& [k, v] : t->frame_columns()) columns[k] = v;
  EXPECT_EQ(columns["slice_passes"], 6);
  EXPECT_EQ(columns["fragments_max"], 6);
  EXPECT_GT(columns["fragments_per_pixel"], 5.0);
}

TEST(DepthSlicing, LevelWithTheSlicePlanesDrawsNothingNonFinite) {
  // A view exactly along the slice planes, level over the plateau: no relief to see, nothing
  // drawn, nothing non-finite.
  const test::Measured level =
      test::measure(plateau_scene(), "depth_slicing", {{"slices", 8}}, View{0, 0}, 48);
  EXPECT_EQ(level.metrics.at("nonfinite_px"), 0);
  EXPECT_EQ(level.metrics.at("union_px"), 0);  // neither the slices nor the truth show a pixel
}

}  // namespace
}  // namespace rl
