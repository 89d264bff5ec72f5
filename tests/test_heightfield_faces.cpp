// Objects from several heightfields (Baboud & Decoret 2006, Section 4.2): the faces' frames, the
// object the faces stand for (the intersection of their solids) on a sphere with stated
// tolerances, the GPU search against the CPU's object, whole frames from every side, and an
// object's depth slices met edge-on. Depth slicing on a plain map:
// techniques/depth_slicing/test_depth_slicing.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "gl/context.h"
#include "gpu/gpu_scene.h"
#include "relief/cell_complex.h"
#include "relief/heightfield_faces.h"
#include "relief/image_io.h"
#include "scene/relief_asset.h"
#include "support/test_support.h"

namespace rl {
namespace {

// The test sphere's radius in its cube's texture space, about the centre: cell_frame fits the
// cube around the mesh with a 2% margin on each side.
constexpr double kRadius = 0.5 / 1.04;

TriangleMesh sphere_mesh() {
  return test::uv_sphere({0, 0, 0}, 1.0, 96, 48);
}

HeightfieldFaces sphere_faces(int count, int resolution, double cop = 0) {
  const TriangleMesh mesh = sphere_mesh();
  return bake_heightfield_faces(mesh, cell_frame(mesh, 1), resolution, count,
                                ReverseProjection{cop});
}

// The share of random cube points (farther than `band` from the sphere's surface) the faces
// classify unlike the sphere.
double misclassified_pct(const HeightfieldFaces& hf, double band) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  int wrong = 0, counted = 0;
  for (int i = 0; i < 40000; ++i) {
    const glm::dvec3 p(u(rng), u(rng), u(rng));
    const double r = glm::length(p - 0.5);
    if (std::abs(r - kRadius) < band) continue;
    ++counted;
    wrong += hf.inside(p, 0.5 / 255) != (r < kRadius);
  }
  return 100.0 * wrong / counted;
}

TEST(HeightfieldFaces, FaceFramesAreRotationsLookingInward) {
  for (int f = 0; f < kCubeFaces; ++f) {
    SCOPED_TRACE(f);
    const glm::dmat3 m = face_from_cube(f);
    EXPECT_NEAR(glm::determinant(m), 1.0, 1e-12);  // not a mirror
    const glm::dmat3 i = m * glm::transpose(m);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) EXPECT_NEAR(i[a][b], a == b ? 1.0 : 0.0, 1e-12);
    // The face's own plane is at depth 0 and the opposite face at depth 1.
    glm::dvec3 on(0.5), opposite(0.5);
    on[f / 2] = f % 2;
    opposite[f / 2] = 1 - f % 2;
    EXPECT_NEAR((m * (on - 0.5) + 0.5).z, 0.0, 1e-12);
    EXPECT_NEAR((m * (opposite - 0.5) + 0.5).z, 1.0, 1e-12);
  }
  EXPECT_EQ(face_from_cube(kTopFace), glm::dmat3(1.0));
  EXPECT_EQ(face_set(3), (std::vector<int>{kTopFace, 1, 3}));
  EXPECT_THROW(face_set(4), std::invalid_argument);
}

TEST(HeightfieldFaces, ASphereIsExactFromTwoFacesAndExtrudedFromOne) {
  // A sphere is convex along every axis, so top and bottom alone bound it (|z| <= the
  // hemispheres' heights is |p| <= r); the top alone extrudes it down to the cube's bottom.
  // Tolerance: points within 1.5 texels of the surface are not judged (bilinear depth).
  const int res = 64;
  const double band = 1.5 / res;
  const double one = misclassified_pct(sphere_faces(1, res), band);
  const double two = misclassified_pct(sphere_faces(2, res), band);
  const double six = misclassified_pct(sphere_faces(6, res), band);
  EXPECT_GT(one, 5.0);  // the column under the equator: 2/3 r^3 pi r^2 ... of the cube
  EXPECT_LT(two, 0.05);
  EXPECT_LT(six, 0.05);
  // Each pole of the sphere is shaded by the face that sees it head-on (faces 4, 5, 0, 1, 2, 3
  // are maps 0 to 5 of the six).
  const HeightfieldFaces all = sphere_faces(6, res);
  const double r = kRadius - 0.2 / res;
  EXPECT_EQ(all.surface_face({0.5, 0.5, 0.5 - r}), 0);
  EXPECT_EQ(all.surface_face({0.5, 0.5, 0.5 + r}), 1);
  EXPECT_EQ(all.surface_face({0.5 - r, 0.5, 0.5}), 2);
  EXPECT_EQ(all.surface_face({0.5 + r, 0.5, 0.5}), 3);
  EXPECT_EQ(all.surface_face({0.5, 0.5 + r, 0.5}), 5);
  // The top face's depth at its centre is the sphere's top, exactly up to 8 bits.
  const HeightfieldFaces hf = sphere_faces(1, res);
  EXPECT_NEAR(hf.behind(0, {0.5, 0.5, 0.5 - kRadius}), 0.0, 1.5 / 255);
}

TEST(HeightfieldFaces, ReversePerspectiveFacesSeeTheirFrustumOnly) {
  const HeightfieldFaces hf = sphere_faces(6, 64, 2.0);
  // A bottom corner of the cube lies outside the top face's frustum (it narrows downwards).
  EXPECT_TRUE(std::isinf(hf.behind(0, {0.02, 0.02, 0.98})));
  EXPECT_GT(hf.behind(0, {0.02, 0.02, 0.98}), 0);
  // Every point is still seen by some face, and the sphere is kept.
  EXPECT_LT(misclassified_pct(hf, 2.0 / 64), 0.1);
}

// Rays through the cube: random ones, ones along the axes and ones inside the faces' planes.
std::vector<ProbeRay> cube_rays() {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1), s(-1, 1);
  std::vector<ProbeRay> rays;
  for (int i = 0; i < 2000; ++i) {
    glm::dvec3 o(u(rng), u(rng), u(rng)), d(s(rng), s(rng), s(rng));
    // Start on the cube's boundary, heading in.
    const int a = i % 3;
    o[a] = i % 2 ? 0.0 : 1.0;
    d[a] = i % 2 ? std::abs(d[a]) + 0.05 : -std::abs(d[a]) - 0.05;
    rays.push_back({glm::vec3(o), glm::vec3(glm::normalize(d))});
  }
  for (int a = 0; a < 3; ++a)
    for (double x : {0.3, 0.5, 0.62}) {
      glm::dvec3 o(x), d(0);
      o[a] = 0;
      d[a] = 1;
      rays.push_back({glm::vec3(o), glm::vec3(d)});  // along an axis: other faces edge-on
    }
  return rays;
}

// The CPU's first point of the ray inside the object: fine steps, then bisection.
double cpu_first_inside(const HeightfieldFaces& hf, glm::dvec3 o, glm::dvec3 d) {
  double t_end = 1e9;
  for (int a = 0; a < 3; ++a)
    if (std::abs(d[a]) > 1e-12) t_end = std::min(t_end, ((d[a] > 0 ? 1.0 : 0.0) - o[a]) / d[a]);
  const int steps = 4096;
  double prev = 0;
  for (int i = 0; i <= steps; ++i) {
    const double t = t_end * i / steps;
    if (hf.inside(o + d * t, 0.5 / 255)) {
      if (i == 0) return 0;
      double lo = prev, hi = t;
      for (int b = 0; b < 30; ++b) {
        const double mid = 0.5 * (lo + hi);
        (hf.inside(o + d * mid, 0.5 / 255) ? hi : lo) = mid;
      }
      return hi;
    }
    prev = t;
  }
  return -1;
}

TEST(HeightfieldFacesGpu, TheRayCasterFindsTheCpuObject) {
  // multi_heightfield's probe against the CPU's object on six reverse-perspective faces: the same
  // hits within two texels for 99% of the rays (a linear step can skip a sliver the CPU's 4096
  // steps find), within its fetch bound on every ray.
  GlContext::shared();
  const int res = 64, linear = 256, binary = 10;
  HeightfieldFaces hf = sphere_faces(6, res, 2.0);
  for (ReliefMap& m : hf.maps) quantize_8bit(m);
  ReliefMap map = hf.maps[0];
  map.faces = std::make_shared<const HeightfieldFaces>(hf);
  GpuRelief relief(map);
  auto t = TechniqueRegistry::instance().create(
      "multi_heightfield", {{"linear_steps", linear}, {"binary_steps", binary}}, "test");
  t->prepare(map);
  const std::vector<ProbeRay> rays = cube_rays();
  const std::vector<ProbeHit> hits = t->probe(map, relief, rays, glm::dvec2(1));
  int disagree = 0, hits_count = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const double cpu = cpu_first_inside(*map.faces, rays[i].origin, rays[i].direction);
    ASSERT_TRUE(std::isfinite(hits[i].t));
    EXPECT_LE(hits[i].fetches, 6 * (linear + 1 + binary));
    hits_count += cpu >= 0;
    if ((cpu >= 0) != hits[i].hit || (hits[i].hit && std::abs(hits[i].t - cpu) > 2.0 / res))
      ++disagree;
  }
  EXPECT_GT(hits_count, 800);
  EXPECT_LT(disagree, int(rays.size() / 100));
}

SceneDesc object_scene(const std::string& mesh, int faces, double cop = 0) {
  SceneDesc s;
  s.name = "object";
  s.relief.mesh_path = mesh;
  s.relief.mesh_up = 1;
  s.relief.faces = faces;
  s.relief.reverse_cop = cop;
  s.relief.native = {64, 64};
  s.proxy = Proxy::Box;
  s.empty_floor = true;
  s.truth = TruthLevel::Mesh;
  s.depth = s.size;
  s.quantize = true;
  return s;
}

TEST(HeightfieldFacesFrames, EveryObjectTechniqueFromAnySide) {
  // Whole frames of the sphere from 6 faces from above, grazing, below, straight down and
  // exactly level (the top and bottom faces' slices edge-on): finite, covering what the mesh
  // covers (within 3% of the pixels). The ray caster is 0.25-0.35 texels off on average; its
  // 2.5-7% of pixels more than a texel off (measured) lie where a face sees the sphere at a
  // grazing angle: the bilinear chord between two steep texels lies inside the sphere, and an
  // intersection of solids cannot undo it. Slicing's error is its slice spacing (32 slices
  // over 64 texels: two texels), so only its coverage is held.
  const std::string mesh = test::write_obj(sphere_mesh(), test::scratch_dir("faces") + "/s.obj");
  for (const View& view : {View{35, 20}, View{3, 100}, View{-40, 250}, View{90, 0}, View{0, 0}}) {
    SCOPED_TRACE("elevation " + std::to_string(view.elevation_deg));
    for (double cop : {0.0, 2.0}) {
      const SceneDesc scene = object_scene(mesh, 6, cop);
      for (const std::string& name : TechniqueRegistry::instance().names()) {
        const TechniqueInfo& info = TechniqueRegistry::instance().find(name)->info;
        if (!cannot_render(info, scene).empty()) continue;
        SCOPED_TRACE(name + " cop " + std::to_string(cop));
        const test::Measured m = test::measure(scene, name, {}, view, 96);
        EXPECT_EQ(m.metrics.at("nonfinite_px"), 0);
        EXPECT_GT(m.metrics.at("covered_px"), 1500);
        EXPECT_LT(m.metrics.at("missed_pct") + m.metrics.at("false_pct"), 3.0);
        if (name == "multi_heightfield") {
          EXPECT_LT(m.metrics.at("wrong_pct"), 8.0);
          EXPECT_LT(m.metrics.at("pos_err_texels_mean"), 0.5);
        }
      }
    }
  }
  // The top face alone, seen from below, is the sphere extruded to the cube's bottom.
  const test::Measured top =
      test::measure(object_scene(mesh, 1), "multi_heightfield", {}, View{-40, 250}, 96);
  EXPECT_GT(top.metrics.at("false_pct"), 10.0);
}

TEST(HeightfieldFacesFrames, FacesThatDisagreeAtTheirEdgesStayFiniteAndBounded) {
  // One face's depths pushed 5% deeper: at the edges it shares with the others the faces now
  // disagree about the silhouette. The object is still their intersection: finite, bounded
  // fetches, and no pixel covered that the faces agreeing did not cover.
  const std::string mesh =
      test::write_obj(sphere_mesh(), test::scratch_dir("faces_disagree") + "/s.obj");
  SceneDesc scene = object_scene(mesh, 6);
  GlContext::shared();
  ReliefMap map = build_relief_asset(scene, 64);
  auto faces = std::make_shared<HeightfieldFaces>(*map.faces);
  for (glm::vec4& t : faces->maps[2].relief)
    if (t.a < 1) t.a = std::min(0.99f, t.a + 0.05f);
  const test::Measured agree = test::measure(scene, "multi_heightfield", {}, View{30, 40}, 96);
  // Render the perturbed object through the same path as measure() does.
  map.faces = faces;
  GpuRelief relief(map);
  GpuBase base(make_base_geometry(scene));
  const Camera camera = make_camera(scene, View{30, 40}, 96, 96);
  auto t = TechniqueRegistry::instance().create("multi_heightfield", {}, "test");
  t->prepare(map);
  FrameInput frame{scene, map, relief, base, camera, scene.effects, nullptr};
  RenderTarget target(96, 96, RenderTarget::Kind::GBuffer);
  target.bind_and_clear();
  render_frame(*t, frame, RenderTarget::Kind::GBuffer);
  GBuffer g;
  target.read_back(g);
  long extra = 0, covered = 0;
  for (size_t i = 0; i < g.size(); ++i) {
    for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(g.position[i][c]));
    EXPECT_LE(g.hit[i].w, 6 * (64 + 1 + 6) + 2);
    covered += g.covered(i);
    extra += g.covered(i) && !agree.technique.covered(i);
  }
  EXPECT_GT(covered, 1500);
  EXPECT_LT(extra, 10);  // edge pixels of the search at most
}

TEST(HeightfieldFacesFrames, DepthSlicesMetEdgeOnStayFinite) {
  // Probe rays lying in an object's slice planes (a level view over a plain map:
  // techniques/depth_slicing/test_depth_slicing.cpp).
  GlContext::shared();
  const HeightfieldFaces hf = sphere_faces(6, 32);
  ReliefMap map = hf.maps[0];
  map.faces = std::make_shared<const HeightfieldFaces>(hf);
  GpuRelief relief(map);
  for (bool view_aligned : {false, true}) {
    auto t = TechniqueRegistry::instance().create(
        "depth_slicing", {{"slices", 16}, {"view_aligned", double(view_aligned)}}, "test");
    const std::vector<ProbeRay> rays = cube_rays();
    const std::vector<ProbeHit> hits = t->probe(map, relief, rays, glm::dvec2(1));
    int found = 0, cpu_found = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      ASSERT_TRUE(std::isfinite(hits[i].t));
      found += hits[i].hit;
      const double cpu = cpu_first_inside(hf, rays[i].origin, rays[i].direction);
      cpu_found += cpu >= 0;
      // A kept slice point is inside the object, so never before its first inside point.
      if (hits[i].hit && cpu >= 0) {
        EXPECT_GE(hits[i].t, cpu - 1.5 / 32);
      }
    }
    // Slices miss only rays that graze the object between two slices.
    EXPECT_GT(found, 0.95 * cpu_found);
    EXPECT_LE(found, cpu_found);
  }
}

}  // namespace
}  // namespace rl
