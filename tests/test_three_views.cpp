// A relief impostor baked along three orthogonal axes, the bake nearest the view drawn
// (Policarpo & Oliveira 2006, Section 4): which bake a view goes to, that its camera sees the
// world the scene's own view sees (direction, roll, scale, light), that a sweep draws every view
// from its nearest bake, and that a grazing view of the quad shows the object again.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "output/result_store.h"
#include "run/cells.h"
#include "support/test_support.h"

namespace rl {
namespace {

constexpr double kTight = 1e-9;

void expect_near(const glm::dvec3& a, const glm::dvec3& b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// A vector of the bake along `from` in the frame of the bake along `to` (no centres: depth 0).
glm::dvec3 carried(const glm::dvec3& v, int from, int to) {
  return carry_to_bake(v, from, 0, to, 0);
}

TEST(ThreeViews, AViewNearestTheScenesOwnAxisIsDrawnAsGiven) {
  for (int up = 0; up < 3; ++up) {
    const AxisView a = nearest_bake_view(View{75, 30}, up);
    EXPECT_EQ(a.up, up);
    EXPECT_EQ(a.view.elevation_deg, 75);
    EXPECT_EQ(a.view.azimuth_deg, 30);
    EXPECT_EQ(a.view.roll_deg, 0);
  }
  // On the boundary between two axes the scene's own wins: 45 degrees at azimuth 0 looks along
  // up and along the quad's u alike.
  EXPECT_EQ(nearest_bake_view(View{45, 0}, 1).up, 1);
  EXPECT_EQ(nearest_bake_view(View{44, 0}, 1).up, 2);  // up y: u is the mesh's z
  EXPECT_EQ(nearest_bake_view(View{46, 0}, 1).up, 1);
  EXPECT_EQ(nearest_bake_view(View{40, 90}, 1).up, 0);  // v is the mesh's x
}

TEST(ThreeViews, EveryViewGoesToTheAxisItLooksAlongMostWithItsDirectionAndRollKept) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> el(-89.9, 89.9), az(0, 360);
  for (int n = 0; n < 300; ++n) {
    const View view{el(rng), az(rng)};
    const int up = n % 3;
    SCOPED_TRACE(testing::Message()
                 << "el " << view.elevation_deg << " az " << view.azimuth_deg << " up " << up);
    const AxisView a = nearest_bake_view(view, up);
    const glm::dvec3 mesh = carried(view_direction(view), up, 2);  // bake along z: x, y, z
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::abs(mesh[k]), std::abs(mesh[a.up]) + kTight);
    // The nearest axis is at most arccos(1/sqrt(3)) from the view: 35.26 degrees of elevation.
    EXPECT_GE(std::abs(a.view.elevation_deg), 35.26 - 1e-6);
    expect_near(view_direction(a.view), carried(view_direction(view), up, a.up), 1e-8);
    expect_near(camera_up(a.view), carried(camera_up(view), up, a.up), 1e-8);
  }
}

TEST(ThreeViews, CarryingAPointTurnsItAboutTheObjectsCentre) {
  // The centre of the object is at depth / 2 below each bake's quad, and stays put.
  expect_near(carry_to_bake({0, 0, -0.3}, 1, 0.6, 0, 0.2), {0, 0, -0.1}, kTight);
  // A point a unit above the centre along the scene's up lies a unit along the other bake's
  // v when that bake's v is the mesh's up axis (bake along x: v is z; scene up z).
  expect_near(carry_to_bake({0, 0, 0.7}, 2, 0.6, 0, 0.2), {0, 1, -0.1}, kTight);
  const glm::dvec3 p(0.3, -0.8, 1.1);
  for (int to = 0; to < 3; ++to)
    expect_near(carry_to_bake(carry_to_bake(p, 1, 0.5, to, 0.3), to, 0.3, 1, 0.5), p, kTight);
}

// A square slab, four times as wide as it is thick: bakes of different depths, so a scale or
// a centre out of step shows.
std::string brick_mesh(const std::string& dir) {
  return test::write_obj(test::layer_boxes({{0.1, 0.9, 0.2, 0.4}}), dir + "/brick.obj");
}

// A sweep of the brick as a three-view impostor; `extra` follows the brick scene's own keys:
// more of them, or further [[scene]] tables.
std::string three_view_sweep(const std::string& mesh, const std::string& views,
                             const std::string& extra = "") {
  return R"([sweep]
name = "three-views"
views = )" +
         views +
         R"(
viewports = [48]
texture_res = [64]
frames = 1
images = false
[[scene]]
name = "brick"
relief = { mesh = ")" +
         mesh + R"(", up = "y", layers = 4, three_views = true }
truth = "mesh"
distance = 2.5
light = [0.4, -0.9, 1.3]
)" + extra +
         R"([[technique]]
name = "multilayer"
linear_steps = 32
)";
}

TEST(ThreeViews, EachBakesCameraSeesTheRaysLightAndObjectsOfTheScenesOwnView) {
  const std::string dir = test::scratch_dir("three_views_cameras");
  const std::string objects =
      "objects = [{ shape = \"sphere\", center = [0.3, 0.2, 0.1], radius = 0.1 }]\n";
  const SweepConfig config =
      parse_sweep_config(three_view_sweep(brick_mesh(dir), "[[30, 10]]", objects), "s.toml", dir);
  ASSERT_EQ(config.scenes.size(), 3u);  // the scene and its bakes along x and z
  const SceneDesc& scene = config.scenes[0];
  const int from = scene.relief.mesh_up;
  for (const SceneDesc& bake : config.scenes) {
    SCOPED_TRACE(bake.name);
    EXPECT_EQ(bake.size, scene.size);  // one quad size: one scale for the three bakes
    expect_near(
        bake.light_position,
        carry_to_bake(scene.light_position, from, scene.depth, bake.relief.mesh_up, bake.depth),
        kTight);
    ASSERT_EQ(bake.objects.size(), 1u);
    expect_near(
        bake.objects[0].center,
        carry_to_bake(scene.objects[0].center, from, scene.depth, bake.relief.mesh_up, bake.depth),
        kTight);
  }
  for (const View view : {View{30, 10}, View{12, 210}, View{-20, 100}, View{50, 300}}) {
    SCOPED_TRACE(testing::Message() << "el " << view.elevation_deg << " az " << view.azimuth_deg);
    const AxisView nearest = nearest_bake_view(view, from);
    const SceneDesc* bake = nullptr;
    for (const SceneDesc& s : config.scenes)
      if (s.relief.mesh_up == nearest.up) bake = &s;
    ASSERT_NE(bake, nullptr);
    // Every pixel's ray, carried from the bake's world to the scene's, is the scene's own.
    const Camera a = make_camera(scene, view, 48, 48);
    const Camera b = make_camera(*bake, nearest.view, 48, 48);
    for (int y : {0, 17, 47})
      for (int x : {0, 30, 47}) {
        glm::dvec3 oa, da, ob, db;
        a.pixel_ray(x, y, oa, da);
        b.pixel_ray(x, y, ob, db);
        expect_near(carry_to_bake(ob, nearest.up, bake->depth, from, scene.depth), oa, 1e-9);
        expect_near(carried(db, nearest.up, from), da, 1e-9);
      }
  }
}

TEST(ThreeViews, ASweepDrawsEveryViewFromItsNearestBakeUnderTheScenesName) {
  const std::string dir = test::scratch_dir("three_views_cells");
  const std::string views = "[[75, 30], [12, 210], [-12, 300], [30, 0], [40, 90]]";
  const SweepConfig config =
      parse_sweep_config(three_view_sweep(brick_mesh(dir), views), "s.toml", dir);
  const std::vector<Cell> cells = expand_cells(config);
  ASSERT_EQ(cells.size(), config.views.size());  // no cell of a bake on its own
  for (size_t i = 0; i < cells.size(); ++i) {
    const Cell& c = cells[i];
    const View& asked = config.views[i];
    const AxisView nearest = nearest_bake_view(asked, 1);
    EXPECT_EQ(c.identity["scene"], "brick");
    EXPECT_EQ(c.identity["elevation_deg"], asked.elevation_deg);
    EXPECT_EQ(c.identity["azimuth_deg"], asked.azimuth_deg);
    EXPECT_EQ(c.identity["bake_axis"], std::string(1, char('x' + nearest.up)));
    EXPECT_EQ(config.scenes[c.scene_index].relief.mesh_up, nearest.up);
    EXPECT_EQ(c.view.elevation_deg, nearest.view.elevation_deg);
    EXPECT_EQ(c.view.roll_deg, nearest.view.roll_deg);
  }
}

TEST(ThreeViews, AGrazingViewOfTheQuadShowsTheObjectAgain) {
  const std::string dir = test::scratch_dir("three_views_grazing");
  const std::string one_view = R"([[scene]]
name = "brick_one_view"
relief = { mesh = ")" + brick_mesh(dir) +
                               R"(", up = "y", layers = 4 }
truth = "mesh"
distance = 2.5
)";
  const SweepConfig config =
      test::run_sweep_in(three_view_sweep(brick_mesh(dir), "[[10, 20]]", one_view), dir);
  ResultStore store(dir + "/out/results.sqlite");
  std::map<std::string, nlohmann::json> rows;
  for (const Cell& c : expand_cells(config)) rows[c.identity["scene"]] = store.row(c.key).value();
  const nlohmann::json &three = rows.at("brick"), &one = rows.at("brick_one_view");
  // Seen 10 degrees off its quad, the one-view impostor's footprint misses most of the object;
  // the bake nearest the view, 80 degrees above its own quad, misses little of it.
  EXPECT_GT(one["beyond_quad_pct"].get<double>(), 40);
  EXPECT_LT(three["beyond_quad_pct"].get<double>(), 10);
  EXPECT_GT(three["covered_px"].get<double>(), 2 * one["covered_px"].get<double>());
  EXPECT_EQ(three["nonfinite_px"].get<double>(), 0);
  EXPECT_LT(three["wrong_pct"].get<double>(), 15);
}

}  // namespace
}  // namespace rl
