// Meshes as heightfields: an analytic pyramid mesh baked and traced.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/triangle_mesh.h"
#include "relief/mesh_bake.h"
#include "scene/clipped_frustum.h"
#include "support/test_support.h"
#include "truth/mesh_truth.h"

namespace rl {
namespace {

// A square pyramid: base [-1, 1]^2 at y = 0, apex (0, 2, 0), y up: height = 2 (1 - max(|x|, |z|)).
// Its height is not 1 on purpose, so a depth that is not normalised by it shows.
std::string pyramid_obj() {
  const std::string path = test::scratch_dir("mesh") + "/pyramid.obj";
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path) << "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 2 0\n"
                         "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 1 3 2\nf 1 4 3\n";
  return path;
}

TEST(MeshBake, PyramidDepthsAndNormalsAreAnalytic) {
  const TriangleMesh mesh = load_mesh(pyramid_obj());
  ASSERT_EQ(mesh.triangles.size(), 6u);
  const BakeFrame frame = bake_frame(mesh, 1);
  EXPECT_DOUBLE_EQ(frame.height, 2.0);
  EXPECT_NEAR(frame.side, 2.0 * 1.08, 1e-12);  // footprint + 4% margin each side
  const int res = 32;
  const ReliefMap map = bake_mesh(mesh, frame, res);
  for (int y = 0; y < res; ++y)
    for (int x = 0; x < res; ++x) {
      // Texel centre in mesh space: u runs along z, v along x (right-handed with y up).
      const double z = frame.origin.z + (x + 0.5) / res * frame.side;
      const double px = frame.origin.x + (y + 0.5) / res * frame.side;
      const double r = std::max(std::abs(px), std::abs(z));
      const double expected = r <= 1 ? r : 1.0;  // depth = 1 - height / 2; outside: the floor
      ASSERT_NEAR(map.depth_texel(x, y), expected, 1e-5) << x << ", " << y;
    }
  // On the face towards +x (y = 2 - 2x) the normal is (2, 1, 0) / sqrt 5; in (u, v, up) = (z, x,
  // y).
  const int x = res / 2, y = int(0.75 * res);  // z ~ 0, x ~ +0.5
  const glm::dvec3 n = decode_normal(glm::dvec4(map.relief[map.index(x, y)]));
  EXPECT_NEAR(n.x, 0.0, 1e-5);
  EXPECT_NEAR(n.y, 2 / std::sqrt(5.0), 1e-5);
  EXPECT_NEAR(n.z, 1 / std::sqrt(5.0), 1e-5);
}

TEST(MeshBake, MeshTruthHitsTheMeshItself) {
  const TriangleMesh mesh = load_mesh(pyramid_obj());
  const BakeFrame frame = bake_frame(mesh, 1);
  MeshTruth truth(mesh, frame);
  // A vertical ray above mesh point (x, z) = (0.3, -0.2) meets height 1.4: depth 0.3.
  const glm::dvec3 top = frame.texture_from_mesh({0.3, 2.0, -0.2});
  TruthHit h = truth.intersect(top - glm::dvec3(0, 0, 0.01), {0, 0, 1}, 0, 2);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.point.z, 0.3, 1e-6);
  ASSERT_TRUE(h.has_normal);
  // The face towards +x, as an affine-space normal (orientation is render_truth's to choose).
  const glm::dvec3 expected = frame.texture_normal({2 / std::sqrt(5.0), 1 / std::sqrt(5.0), 0});
  EXPECT_NEAR(std::abs(glm::dot(glm::normalize(h.normal), expected)), 1.0, 1e-9);
  // Beside the pyramid there is nothing: no floor in a mesh.
  EXPECT_FALSE(truth.intersect({0.01, 0.01, -0.01}, {0, 0, 1}, 0, 2).hit);
  EXPECT_EQ(truth.primary_rays(), 2u);
}

// load_mesh() keeps what it read, by the file's bytes: the same file again is the same mesh,
// and the file rewritten in place (same size, within the same clock tick as like as not) is read
// again, not served from memory.
TEST(MeshBake, AMeshRewrittenInPlaceIsReadAgain) {
  const std::string path = pyramid_obj();
  const TriangleMesh first = load_mesh(path);
  const TriangleMesh again = load_mesh(path);
  EXPECT_EQ(again.positions, first.positions);
  EXPECT_EQ(again.triangles.size(), first.triangles.size());
  // The apex raised from y = 2 to 3: one byte changes, the size does not.
  std::ofstream(path) << "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 3 0\n"
                         "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 1 3 2\nf 1 4 3\n";
  const TriangleMesh edited = load_mesh(path);
  EXPECT_EQ(edited.hi.y, 3.0);
  EXPECT_EQ(first.hi.y, 2.0);
}

TEST(MeshBake, UnreadableMeshIsAConfigError) {
  EXPECT_THROW(load_mesh("/no/such/mesh.obj"), ConfigError);
  const std::string empty = test::scratch_dir("empty") + ".obj";
  std::ofstream(empty) << "# no faces\nv 0 0 0\n";
  EXPECT_THROW(load_mesh(empty), ConfigError);
}

}  // namespace
}  // namespace rl

namespace rl {
namespace {

// A closed solid has no boundary and no non-manifold edge; a hole's rim and a fin are counted,
// with vertices split by the file (per-face copies) welded by position first.
TEST(MeshClosure, CountsHolesAndFinsOfAWeldedMesh) {
  TriangleMesh cube;
  const glm::vec3 corner[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                               {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
  for (const auto& q : quads) {  // each face its own copy of its corners, as an OBJ with normals
    const uint32_t base = uint32_t(cube.positions.size());
    for (int k = 0; k < 4; ++k) cube.positions.push_back(corner[q[k]]);
    cube.triangles.push_back({base, base + 1, base + 2});
    cube.triangles.push_back({base, base + 2, base + 3});
  }
  EXPECT_TRUE(mesh_closure(cube).closed());
  TriangleMesh holed = cube;
  holed.triangles.pop_back();  // half of one face gone: its three edges lose a neighbour
  EXPECT_EQ(mesh_closure(holed).boundary_edges, 3);
  EXPECT_EQ(mesh_closure(holed).non_manifold_edges, 0);
  TriangleMesh fin = cube;
  fin.positions.push_back({0.5f, 0.5f, 2.0f});
  fin.triangles.push_back({4 + 1, 4 + 2, uint32_t(fin.positions.size() - 1)});  // on the top edge
  EXPECT_EQ(mesh_closure(fin).non_manifold_edges, 1);
  EXPECT_EQ(mesh_closure(fin).boundary_edges, 2);
}

// The teapot is open at the spout and under the lid: encoded as a cell complex, the run says so.
TEST(MeshClosure, AnOpenMeshWhereASolidIsNeededIsWarnedInTheLog) {
  const std::string dir = test::scratch_dir("open-cells");
  test::run_sweep_in(R"(
[sweep]
name = "open"
views = [[45, 30]]
viewports = [32]
frames = 1
warmup = 0
images = false
[[scene]]
name = "teapot_cells"
relief = { cells = "assets/meshes/teapot.obj", grid = 2, resolution = 16 }
[[technique]]
name = "cell_complex"
)",
                     dir);
  std::ifstream in(dir + "/out/run.log");
  const std::string log((std::istreambuf_iterator<char>(in)), {});
  const TriangleMesh teapot =
      load_mesh(std::string(RELIEFLAB_SOURCE_DIR) + "/assets/meshes/teapot.obj");
  const MeshClosure c = mesh_closure(teapot);
  ASSERT_FALSE(c.closed());
  EXPECT_NE(log.find("scene teapot_cells: mesh "), std::string::npos) << log;
  EXPECT_NE(log.find("is not closed (" + std::to_string(c.boundary_edges) + " boundary edge(s)"),
            std::string::npos)
      << log;
}

TEST(ReverseProjection, RoundTripsAndKeepsLinesStraight) {
  const ReverseProjection p{3.0};
  const glm::dvec3 a(0.2, 0.7, 0.4);
  const glm::dvec3 back = p.affine_from_texture(p.texture_from_affine(a));
  EXPECT_NEAR(glm::distance(a, back), 0.0, 1e-12);
  // The top is unchanged; the bottom of the frustum spans the whole texture.
  EXPECT_NEAR(glm::distance(p.texture_from_affine({0.3, 0.6, 0}), glm::dvec3(0.3, 0.6, 0)), 0,
              1e-15);
  EXPECT_NEAR(p.texture_from_affine(p.affine_from_texture({1, 0, 1})).x, 1.0, 1e-12);
  // Three collinear affine points stay collinear (a projective map).
  const glm::dvec3 q0(0.1, 0.2, -0.5), q1(0.4, 0.9, 0.8);
  const glm::dvec3 t0 = p.texture_from_affine(q0), t1 = p.texture_from_affine(q1);
  const glm::dvec3 tm = p.texture_from_affine(0.3 * q0 + 0.7 * q1);
  EXPECT_NEAR(glm::length(glm::cross(tm - t0, t1 - t0)), 0.0, 1e-12);
}

SceneDesc teapot_scene(double cop, TruthLevel truth) {
  SceneDesc s;
  s.name = "teapot";
  s.proxy = Proxy::Box;
  s.truth = truth;
  s.empty_floor = true;
  s.relief.mesh_path = std::string(RELIEFLAB_SOURCE_DIR) + "/assets/meshes/teapot.obj";
  s.relief.native = {128, 128};
  s.projection.cop = cop;
  const TriangleMesh mesh = load_mesh(s.relief.mesh_path);
  const BakeFrame frame = bake_frame(mesh, 1);
  s.depth = s.size * frame.height / frame.side;
  s.distance = 1.7;
  return s;
}

TEST(ReverseProjection, ShaderAndTruthProjectAlike) {
  // Against the truth of its own (reverse-perspective) heightfield, the exact walk must agree
  // as it does orthographically: the shader's projection and the truth's are the same map.
  test::Measured m = test::measure(teapot_scene(2.0, TruthLevel::Sampled), "relief_exact_bilinear",
                                   {}, View{30, 30}, 128);
  EXPECT_GT(m.metrics.at("covered_px"), 1000);
  EXPECT_LE(m.metrics.at("missed_pct") + m.metrics.at("false_pct"), 0.5);
  EXPECT_LE(m.metrics.at("pos_err_p99"), 5e-3);
}

TEST(ReverseProjection, CapturesMoreOfTheTeapotThanAnOrthographicBake) {
  // Section 4's claim, against the mesh itself: less of the overhangs is extruded to the floor.
  test::Measured ortho = test::measure(teapot_scene(0.0, TruthLevel::Mesh), "relief_exact_bilinear",
                                       {}, View{30, 30}, 128);
  test::Measured reverse = test::measure(teapot_scene(2.0, TruthLevel::Mesh),
                                         "relief_exact_bilinear", {}, View{30, 30}, 128);
  std::printf("false coverage against the mesh: orthographic %.2f%%, reverse perspective %.2f%%\n",
              ortho.metrics.at("false_pct"), reverse.metrics.at("false_pct"));
  EXPECT_LT(reverse.metrics.at("false_pct"), 0.6 * ortho.metrics.at("false_pct"));
}

}  // namespace
}  // namespace rl

namespace rl {
namespace {

using Faces = std::vector<std::vector<glm::dvec3>>;

// Volume and area-weighted normal sum of a polyhedron given by its faces (wound inward in affine
// space, as the proxy is: scene/clipped_frustum.h): a closed surface
// sums to zero; the volume comes from the divergence theorem over fan triangles.
void measure(const Faces& faces, double& volume, glm::dvec3& normal_sum) {
  volume = 0;
  normal_sum = glm::dvec3(0);
  for (const auto& f : faces)
    for (size_t k = 1; k + 1 < f.size(); ++k) {
      volume -= glm::dot(f[0], glm::cross(f[k], f[k + 1])) / 6.0;  // inward: minus
      normal_sum += glm::cross(f[k] - f[0], f[k + 1] - f[0]) / 2.0;
    }
}

// Baboud & Decoret, Section 4.1: the frustum cut to a box is a closed solid, outward wound, no
// larger than either; a box inside the frustum comes back whole, and a box around it leaves
// the frustum as it was.
TEST(ClippedFrustum, IsTheClosedIntersectionOfFrustumAndBox) {
  const ReverseProjection p{3.0};
  Faces whole = clipped_frustum_faces(p, AffineBox{glm::dvec3(-1), glm::dvec3(2)});
  double frustum_volume = 0, v = 0;
  glm::dvec3 sum;
  measure(whole, frustum_volume, sum);
  EXPECT_EQ(whole.size(), 6u);
  EXPECT_LT(glm::length(sum), 1e-10);
  // The frustum: a truncated pyramid from the unit top down to (1 - 1/3)^2 at depth 1.
  const double bottom = std::pow(1.0 - 1.0 / 3.0, 2);
  EXPECT_NEAR(frustum_volume, (1.0 + bottom + std::sqrt(bottom)) / 3.0, 1e-12);

  const AffineBox inside{glm::dvec3(0.4, 0.3, 0.2), glm::dvec3(0.6, 0.5, 0.5)};
  measure(clipped_frustum_faces(p, inside), v, sum);
  EXPECT_NEAR(v, 0.2 * 0.2 * 0.3, 1e-12);
  EXPECT_LT(glm::length(sum), 1e-10);

  // A box poking out of a side and through the bottom: closed, smaller than both.
  const AffineBox across{glm::dvec3(0.5, 0.1, 0.5), glm::dvec3(1.5, 0.9, 1.5)};
  const Faces cut = clipped_frustum_faces(p, across);
  measure(cut, v, sum);
  EXPECT_LT(glm::length(sum), 1e-10);
  EXPECT_GT(v, 0.0);
  EXPECT_LT(v, frustum_volume);
  EXPECT_LT(v, 1.0 * 0.8 * 1.0);
  for (const auto& f : cut)
    for (const glm::dvec3& a : f) {
      const glm::dvec3 t = p.texture_from_affine(a);
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(t[k], -1e-9);
        EXPECT_LE(t[k], 1 + 1e-9);
        EXPECT_GE(a[k], across.lo[k] - 1e-9);
        EXPECT_LE(a[k], across.hi[k] + 1e-9);
      }
    }
}

// The bounds hold every column that can stop a ray: one solid texel's column from its surface
// to the floor, a texel wider each way; an empty floor holds nothing.
TEST(ClippedFrustum, BoundsHoldTheColumnsThatCanStopARay) {
  const ReverseProjection p{3.0};
  ReliefMap map = test::map_from_depths(8, 8, std::vector<float>(64, 1.0f));
  AffineBox box;
  EXPECT_FALSE(relief_affine_bounds(map, p, true, box));
  map.relief[size_t(3) * 8 + 4].a = 0.25f;
  ASSERT_TRUE(relief_affine_bounds(map, p, true, box));
  for (double u : {3.0 / 8, 6.0 / 8})
    for (double v : {2.0 / 8, 5.0 / 8})
      for (double d : {0.25, 1.0}) {
        const glm::dvec3 a = p.affine_from_texture({u, v, d});
        for (int k = 0; k < 3; ++k) {
          EXPECT_GE(a[k], box.lo[k] - 1e-12);
          EXPECT_LE(a[k], box.hi[k] + 1e-12);
        }
      }
  EXPECT_NEAR(box.lo.z, p.affine_from_texture({0.5, 0.5, 0.25}).z, 1e-12);
  // A solid floor: every texel stands, at least at depth 1.
  ASSERT_TRUE(relief_affine_bounds(map, p, false, box));
  EXPECT_NEAR(box.hi.x - box.lo.x, 1.0 - 1.0 / 3.0, 1e-12);  // the frustum's floor
}

}  // namespace
}  // namespace rl
