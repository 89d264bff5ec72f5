// The truth of a relief on a curved base (truth/displaced_truth.h) against references that share
// no code with it: a closed form on a base whose normals are radial, where the fibre through a
// point is the ray from the centre; the sheet of its front end against the relief sampled
// directly; and its own stated bound on every base kind.
#include <algorithm>
#include <cmath>
#include <optional>
#include <random>

#include <gtest/gtest.h>

#include "metrics/metrics.h"
#include "scene/base_mesh.h"
#include "scene/relief_asset.h"
#include "support/test_support.h"
#include "truth/displaced_truth.h"
#include "truth/min_pyramid.h"
#include "truth/truth_render.h"

namespace rl {
namespace {

SceneDesc curved_scene(const std::string& base, const std::string& relief, int res) {
  SceneDesc s = test::procedural_scene(relief, res, 0.08);
  s.name = base + "_" + relief;
  s.base.kind = base;
  s.base.segments = 12;
  return s;
}

// A relief on a generated or shipped base, with its truth.
struct CurvedCase {
  SceneDesc scene;
  ReliefMap map;
  BaseMesh mesh;
  std::unique_ptr<DisplacedTruth> truth;
};

CurvedCase curved_case(const std::string& base, const std::string& relief, int res) {
  CurvedCase c{curved_scene(base, relief, res), {}, {}, nullptr};
  c.map = build_relief_asset(c.scene, res);
  c.mesh = make_base_mesh(c.scene.base, c.scene.size, c.scene.tile);
  c.truth = std::make_unique<DisplacedTruth>(c.mesh, c.map, c.scene.depth);
  return c;
}

// A sphere of radius `radius` about the origin: an octahedron's faces split n x n and pushed
// onto it, normals radial, uvs the projection along z (0.5 + x, 0.5 + y) / (2 radius): no seam
// and no pole, so the relief on it is continuous everywhere.
BaseMesh radial_sphere(double radius, int n) {
  BaseMesh m;
  for (int face = 0; face < 8; ++face) {
    glm::dvec3 a(face & 1 ? 1 : -1, 0, 0), b(0, face & 2 ? 1 : -1, 0), c(0, 0, face & 4 ? 1 : -1);
    if (glm::dot(glm::cross(b - a, c - a), a + b + c) < 0) std::swap(b, c);
    const unsigned first = unsigned(m.position.size());
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i + j <= n; ++i) {
        const glm::dvec3 dir =
            glm::normalize(a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n));
        m.position.push_back(radius * dir);
        m.normal.push_back(dir);
        m.uv.push_back(glm::dvec2(0.5) + glm::dvec2(dir.x, dir.y) * 0.5);
        m.dpdu.push_back({1, 0, 0});
        m.dpdv.push_back({0, 1, 0});
      }
    auto at = [&](int i, int j) { return first + unsigned(j * (n + 1) - j * (j - 1) / 2 + i); };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i + j < n; ++i) {
        m.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 1 < n) m.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  m.radius = radius;
  return m;
}

// GL_LINEAR + GL_REPEAT depth of the map at (u, v), written out here.
double bilinear_depth(const ReliefMap& map, double u, double v) {
  const double x = u * map.width - 0.5, y = v * map.height - 0.5;
  const double fx = std::floor(x), fy = std::floor(y), ax = x - fx, ay = y - fy;
  auto texel = [&](double i, double j) {
    const long w = map.width, h = map.height;
    return double(map.relief[size_t(((long(j) % h + h) % h) * w + (long(i) % w + w) % w)].a);
  };
  return (1 - ay) * ((1 - ax) * texel(fx, fy) + ax * texel(fx + 1, fy)) +
         ay * ((1 - ax) * texel(fx, fy + 1) + ax * texel(fx + 1, fy + 1));
}

// A base whose vertices lie on a sphere about the origin with radial normals: on each flat
// triangle the interpolated normal is (P - 0) / R, so the relief's fibre through a point X is
// the ray from the origin through X. Where that ray meets the triangle's plane at distance rho,
// the surface lies at rho - depth d(uv); X is at or below it when |X| <= rho - depth d(uv).
class RadialReference {
 public:
  RadialReference(const BaseMesh& mesh, const ReliefMap& map, double depth)
      : mesh_(mesh), map_(map), depth_(depth) {}

  // How far below the surface X lies (>= 0: at or below), or nothing outside every cone.
  std::optional<double> below(const glm::dvec3& x) const {
    const glm::dvec3 w = glm::normalize(x);
    for (size_t k = 0; k < mesh_.triangles.size(); ++k) {
      const size_t t = (last_ + k) % mesh_.triangles.size();
      const glm::uvec3& tri = mesh_.triangles[t];
      const glm::dvec3 a = mesh_.position[tri.x], b = mesh_.position[tri.y],
                       c = mesh_.position[tri.z];
      const glm::dvec3 n = glm::cross(b - a, c - a);
      if (glm::length(n) < 1e-12) continue;       // a pole cap's sliver
      if (glm::dot(w, a + b + c) <= 0) continue;  // the cone's opposite
      // Inside the cone: on the inner side of the three planes through the origin and an edge.
      const double sa = glm::dot(w, glm::cross(a, b)), sb = glm::dot(w, glm::cross(b, c)),
                   sc = glm::dot(w, glm::cross(c, a));
      if (!((sa >= 0 && sb >= 0 && sc >= 0) || (sa <= 0 && sb <= 0 && sc <= 0))) continue;
      const double rho = glm::dot(a, n) / glm::dot(w, n);
      const glm::dvec3 q = rho * w;
      const double area = glm::dot(n, n);
      const double b1 = glm::dot(glm::cross(q - a, c - a), n) / area;
      const double b2 = glm::dot(glm::cross(b - a, q - a), n) / area;
      const glm::dvec2 uv =
          (1 - b1 - b2) * mesh_.uv[tri.x] + b1 * mesh_.uv[tri.y] + b2 * mesh_.uv[tri.z];
      last_ = t;
      return rho - depth_ * bilinear_depth(map_, uv.x, uv.y) - glm::length(x);
    }
    return std::nullopt;
  }

  // The first t at which the ray is at or below the surface: sampled every `step` from where it
  // enters the sphere of radius `radius` (twenty times finer where it passes within four steps
  // of the surface, so a ray that only grazes a crest is not stepped over), then bisected; NaN
  // where it misses.
  double first_hit(const glm::dvec3& o, const glm::dvec3& d, double radius, double step,
                   double t_min = -1e300) const {
    const double b = glm::dot(o, d), c = glm::dot(o, o) - radius * radius, disc = b * b - c;
    if (disc <= 0) return std::nan("");
    const double t0 = std::max(t_min, -b - std::sqrt(disc)), t1 = -b + std::sqrt(disc);
    if (at_or_below_at(o + t0 * d)) return t0;
    auto at_or_below = [&](double t) {
      const std::optional<double> g = below(o + t * d);
      return g && *g >= 0;
    };
    for (double lo = t0; lo <= t1; lo += step) {
      const std::optional<double> g = below(o + (lo + step) * d);
      const int parts = g && *g > -4 * step ? 20 : 1;
      for (int k = 1; k <= parts; ++k) {
        double hi = lo + step * k / parts;
        if (!at_or_below(hi)) continue;
        double from = lo + step * (k - 1) / parts;
        for (int i = 0; i < 60; ++i) {
          const double mid = 0.5 * (from + hi);
          (at_or_below(mid) ? hi : from) = mid;
        }
        return hi;
      }
    }
    return std::nan("");
  }

 private:
  bool at_or_below_at(const glm::dvec3& x) const {
    const std::optional<double> g = below(x);
    return g && *g >= 0;
  }
  const BaseMesh& mesh_;
  const ReliefMap& map_;
  double depth_;
  mutable size_t last_ = 0;
};

TEST(CurvedBaseTruth, MatchesAClosedFormOnARadialBaseFromOneToNinetyDegrees) {
  // Primary rays: hit or miss as the closed form, and where; shadow rays: met or not.
  for (const char* relief : {"sines", "bricks"}) {
    const SceneDesc scene = curved_scene("sphere", relief, 32);
    const ReliefMap map = build_relief_asset(scene, 32);
    const BaseMesh mesh = radial_sphere(0.5 * scene.size, 6);
    const DisplacedTruth truth(mesh, map, scene.depth);
    const RadialReference reference(mesh, map, scene.depth);
    const double texel = texel_world(mesh, MapSize{map.width, map.height});
    for (double elevation : {1.0, 5.0, 20.0, 45.0, 90.0}) {
      const Camera camera = make_camera(scene, View{elevation, 25}, 40, 40);
      long hits = 0, disagree = 0, shadows = 0, shadow_disagree = 0;
      double worst = 0;
      const glm::dvec3 light = glm::normalize(glm::dvec3(0.3, -0.8, 0.5));
      for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
          glm::dvec3 eye, dir;
          camera.pixel_ray(x, y, eye, dir);
          const double t = reference.first_hit(eye, dir, 0.5 * scene.size + 1e-9, 0.01 * texel);
          const DisplacedHit h = truth.intersect(eye, dir, camera.far_plane);
          if (h.hit != !std::isnan(t)) {
            ++disagree;
            continue;
          }
          if (!h.hit) continue;
          ++hits;
          worst = std::max(worst, glm::distance(h.position, eye + t * dir) / texel);
          // A shadow ray from the hit, started in its prism: met or not, as the closed form.
          const double t_min = 1e-4 * scene.depth;
          const bool shadowed = truth.occluded(h.position, light, t_min, 2.0, h.base_triangle);
          const double t_shadow =
              reference.first_hit(h.position, light, 0.5 * scene.size + 1e-9, 0.01 * texel, t_min);
          shadow_disagree += shadowed == std::isnan(t_shadow);
          shadows += shadowed;
        }
      std::printf("%s at %g degrees: %ld hits, worst %.2g texel; %ld in shadow, %ld disagree\n",
                  relief, elevation, hits, worst, shadows, shadow_disagree);
      SCOPED_TRACE(std::string(relief) + " at " + std::to_string(elevation) + " degrees");
      EXPECT_GT(hits, 100);
      EXPECT_EQ(disagree, 0);
      EXPECT_LE(worst, 0.05);
      EXPECT_GT(shadows, 50);
      EXPECT_LE(shadow_disagree, hits / 200);  // a shadow ray grazing the relief: either way
    }
  }
}

// The relief of the base mesh at barycentrics (b1, b2) of triangle t, from the mesh's own data:
// the point and its depth below the base (world).
glm::dvec3 relief_point(const BaseMesh& mesh, const ReliefMap& map, double depth, size_t t,
                        double b1, double b2, double& s) {
  const glm::uvec3& tri = mesh.triangles[t];
  const double b0 = 1 - b1 - b2;
  const glm::dvec3 p =
      b0 * mesh.position[tri.x] + b1 * mesh.position[tri.y] + b2 * mesh.position[tri.z];
  const glm::dvec3 n =
      glm::normalize(b0 * mesh.normal[tri.x] + b1 * mesh.normal[tri.y] + b2 * mesh.normal[tri.z]);
  const glm::dvec2 uv = b0 * mesh.uv[tri.x] + b1 * mesh.uv[tri.y] + b2 * mesh.uv[tri.z];
  s = depth * bilinear_depth(map, uv.x, uv.y);
  return p - s * n;
}

// The front end may only ever be a speed knob: the relief never lies outside its sheet. Sampled
// at random barycentrics (at least 64 per base triangle), on the steepest map (the bricks' walls).
TEST(CurvedBaseTruth, TheSheetLiesOutsideTheReliefOnEveryBase) {
  for (const char* kind : {"sphere", "torus", "teapot", "cube"}) {
    const auto [scene, map, mesh, truth] = curved_case(kind, "bricks", 64);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0, 1);
    long sampled = 0, outside = 0;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      if (!truth->prisms().usable(unsigned(t))) continue;
      for (size_t k = 0; k < std::max<size_t>(64, 20000 / mesh.triangles.size()); ++k) {
        double b1 = unit(rng), b2 = unit(rng), s = 0;
        if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
        const glm::dvec3 x = relief_point(mesh, map, scene.depth, t, b1, b2, s);
        outside += truth->sheets().outside(x, PrismPoint{unsigned(t), b1, b2, s});
        ++sampled;
      }
    }
    EXPECT_GT(sampled, 1000) << kind;
    EXPECT_EQ(outside, 0) << kind << ": " << outside << " of " << sampled;
  }
}

// A sheet sixteen times coarser makes the walk longer, not the answer different.
TEST(CurvedBaseTruth, TheSheetIsOnlyASpeedKnob) {
  const SceneDesc scene = curved_scene("torus", "bricks", 64);
  const ReliefMap map = build_relief_asset(scene, 64);
  const BaseMesh mesh = make_base_mesh(scene.base, scene.size, scene.tile);
  const DisplacedTruth fine(mesh, map, scene.depth, 1.0), coarse(mesh, map, scene.depth, 16.0);
  ASSERT_GT(fine.subdivision(), coarse.subdivision());
  const double texel = texel_world(mesh, MapSize{map.width, map.height});
  const Camera camera = make_camera(scene, View{20, 40}, 64, 64);
  long both = 0, differ = 0;
  double worst = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      glm::dvec3 eye, dir;
      camera.pixel_ray(x, y, eye, dir);
      const DisplacedHit a = fine.intersect(eye, dir, camera.far_plane);
      const DisplacedHit b = coarse.intersect(eye, dir, camera.far_plane);
      differ += a.hit != b.hit;
      if (!(a.hit && b.hit)) continue;
      ++both;
      worst = std::max(worst, glm::distance(a.position, b.position) / texel);
    }
  EXPECT_GT(both, 1000);
  EXPECT_EQ(differ, 0);
  EXPECT_LE(worst, 1e-3);
}

// Every base kind at grazing, oblique and top views: the stated per-pixel bound is within the
// target on all but 0.1% of the covered pixels, so no row rests on a flagged truth.
TEST(CurvedBaseTruth, StatesABoundWithinTheTargetOnEveryBase) {
  for (const char* kind : {"sphere", "torus", "teapot", "cube"}) {
    const auto [scene, map, mesh, truth] = curved_case(kind, "pyramids", 64);
    const double texel = texel_world(mesh, MapSize{map.width, map.height});
    for (double elevation : {5.0, 45.0, 90.0}) {
      const GBuffer g =
          render_truth(*truth, map, scene, make_camera(scene, View{elevation, 30}, 48, 48), {});
      const TruthBoundStats bound = truth_bound_stats(g, texel);
      EXPECT_GT(bound.covered, 200) << kind << " at " << elevation;
      EXPECT_LE(bound.uncertain * 1000, bound.covered) << kind << " at " << elevation;
    }
  }
}

// Secondary rays start under the sheet, where Embree alone would not see the relief: the walk
// starts in the hit's prism. A relief of one depth on a flat base occludes no hemisphere ray;
// on a sphere, no hit's ray back to the eye along the path that reached it is blocked. (On the
// sphere a hemisphere ray may be: the flat triangles displaced along interpolated normals tilt
// the surface by up to half the angle between neighbouring normals.)
TEST(CurvedBaseTruth, SecondaryRaysFromAConstantReliefLeaveIt) {
  SceneDesc scene = test::procedural_scene("constant", 32, 0.08, false, {{"value", 0.6}});
  scene.effects.add(Effect::AmbientOcclusion);
  scene.ao.samples = 16;
  const ReliefMap map = build_relief_asset(scene, 32);
  const DisplacedTruth flat(make_base_mesh(BaseDesc{"plane", "", 1}, scene.size, scene.tile), map,
                            scene.depth);
  TruthStats stats;
  const GBuffer g = render_truth(flat, map, scene, make_camera(scene, View{35, 20}, 40, 40),
                                 scene.effects, &stats);
  long covered = 0, occluded = 0;
  for (size_t i = 0; i < g.size(); ++i) {
    covered += g.covered(i);
    occluded += g.covered(i) && g.aux[i].x < 1.0f;
  }
  EXPECT_GT(covered, 300);
  EXPECT_GT(stats.ao_rays, uint64_t(covered) * 8);
  EXPECT_EQ(occluded, 0);

  scene.base.kind = "sphere";
  scene.base.segments = 16;
  const DisplacedTruth sphere(make_base_mesh(scene.base, scene.size, scene.tile), map, scene.depth);
  const Camera camera = make_camera(scene, View{35, 20}, 40, 40);
  long hits = 0, blocked = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      glm::dvec3 eye, dir;
      camera.pixel_ray(x, y, eye, dir);
      const DisplacedHit h = sphere.intersect(eye, dir, camera.far_plane);
      if (!h.hit) continue;
      ++hits;
      blocked += sphere.occluded(h.position, -dir, 1e-4 * scene.depth, h.t, h.base_triangle);
    }
  EXPECT_GT(hits, 500);
  EXPECT_EQ(blocked, 0);
}

// The sheet's least depths: never above the least texel of the box (wrapping like GL_REPEAT),
// exact for one texel, on a map whose sides are not powers of two.
TEST(CurvedBaseTruth, TheMinPyramidNeverExceedsTheBoxsLeastTexel) {
  ReliefMap map;
  map.width = 37;
  map.height = 23;
  map.relief.resize(size_t(map.width) * size_t(map.height));
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> depth(0, 1);
  for (glm::vec4& t : map.relief) t.a = depth(rng);
  const MinPyramid pyramid(map);
  std::uniform_int_distribution<long> start(-80, 80), extent(0, 50);
  for (int k = 0; k < 2000; ++k) {
    const long x0 = start(rng), y0 = start(rng), x1 = x0 + extent(rng), y1 = y0 + extent(rng);
    double least = 1e9;
    for (long y = y0; y <= y1; ++y)
      for (long x = x0; x <= x1; ++x)
        least = std::min(
            least, double(map.depth_texel(int(((x % 37) + 37) % 37), int(((y % 23) + 23) % 23))));
    ASSERT_LE(pyramid.least(x0, x1, y0, y1), least) << x0 << ".." << x1 << ", " << y0 << ".." << y1;
    if (x0 == x1 && y0 == y1) {
      ASSERT_EQ(pyramid.least(x0, x1, y0, y1), least);
    }
  }
  for (long x = -40; x < 40; ++x)
    ASSERT_EQ(pyramid.least(x, x, 5, 5), map.depth_texel(int(((x % 37) + 37) % 37), 5));
}

}  // namespace
}  // namespace rl
