// Meshes as heightfields: an analytic pyramid mesh baked and traced.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "relief/mesh_bake.h"
#include "support/test_support.h"
#include "truth/mesh_truth.h"

namespace rl {
namespace {

// A square pyramid: base [-1, 1]^2 at y = 0, apex (0, 1, 0), y up; height = 1 - max(|x|, |z|).
std::string pyramid_obj() {
  const std::string path = test::scratch_dir("mesh") + "/pyramid.obj";
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path) << "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 1 0\n"
                         "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 1 3 2\nf 1 4 3\n";
  return path;
}

TEST(MeshBake, PyramidDepthsAndNormalsAreAnalytic) {
  const TriangleMesh mesh = load_mesh(pyramid_obj());
  ASSERT_EQ(mesh.triangles.size(), 6u);
  const BakeFrame frame = bake_frame(mesh, 1);
  EXPECT_DOUBLE_EQ(frame.height, 1.0);
  EXPECT_NEAR(frame.side, 2.0 * 1.08, 1e-12);  // footprint + 4% margin each side
  const int res = 32;
  const ReliefMap map = bake_mesh(mesh, frame, res);
  for (int y = 0; y < res; ++y)
    for (int x = 0; x < res; ++x) {
      // Texel centre in mesh space: u runs along z, v along x (right-handed with y up).
      const double z = frame.origin.z + (x + 0.5) / res * frame.side;
      const double px = frame.origin.x + (y + 0.5) / res * frame.side;
      const double r = std::max(std::abs(px), std::abs(z));
      const double expected = r <= 1 ? r : 1.0;  // depth = 1 - height; outside: the floor
      ASSERT_NEAR(map.depth_texel(x, y), expected, 1e-5) << x << ", " << y;
    }
  // On the face towards +x the normal is (1, 1, 0) / sqrt 2; in (u, v, up) = (z, x, y).
  const int x = res / 2, y = int(0.75 * res);  // z ~ 0, x ~ +0.5
  const glm::dvec3 n = decode_normal(glm::dvec4(map.relief[map.index(x, y)]));
  EXPECT_NEAR(n.x, 0.0, 1e-5);
  EXPECT_NEAR(n.y, std::sqrt(0.5), 1e-5);
  EXPECT_NEAR(n.z, std::sqrt(0.5), 1e-5);
}

TEST(MeshBake, MeshTruthHitsTheMeshItself) {
  const TriangleMesh mesh = load_mesh(pyramid_obj());
  const BakeFrame frame = bake_frame(mesh, 1);
  MeshTruth truth(mesh, frame);
  // A vertical ray above mesh point (x, z) = (0.3, -0.2) meets height 0.7: depth 0.3.
  const glm::dvec3 top = frame.texture_from_mesh({0.3, 1.0, -0.2});
  TruthHit h = truth.intersect(top - glm::dvec3(0, 0, 0.01), {0, 0, 1}, 0, 2);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.point.z, 0.3, 1e-6);
  ASSERT_TRUE(h.has_normal);
  EXPECT_LT(h.normal.z, 0);  // faces up (towards smaller depth), i.e. towards the ray's origin
  // Beside the pyramid there is nothing: no floor in a mesh.
  EXPECT_FALSE(truth.intersect({0.01, 0.01, -0.01}, {0, 0, 1}, 0, 2).hit);
  EXPECT_EQ(truth.primary_rays(), 2u);
}

TEST(MeshBake, UnreadableMeshIsAConfigError) {
  EXPECT_THROW(load_mesh("/no/such/mesh.obj"), ConfigError);
  const std::string empty = test::scratch_dir("empty") + ".obj";
  std::ofstream(empty) << "# no faces\nv 0 0 0\n";
  EXPECT_THROW(load_mesh(empty), ConfigError);
}

}  // namespace
}  // namespace rl
