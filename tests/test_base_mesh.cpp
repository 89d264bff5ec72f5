// Base meshes for curved reliefs: uv tangent frames with mapping scale, and the per-vertex
// quadric curvature of chapter 5 (Listing 5.8) on surfaces of known curvature.
#include <cmath>
#include <optional>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "core/error.h"
#include "scene/base_mesh.h"

namespace rl {
namespace {

constexpr double kPi = glm::pi<double>();

// A ring of n points at distance h around the origin of a tangent frame, on the surface z(x, y).
template <typename Surface>
std::vector<glm::dvec3> ring(int n, double h, Surface&& z) {
  std::vector<glm::dvec3> r;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n + 0.3;
    const double x = h * std::cos(a), y = h * std::sin(a);
    r.push_back({x, y, z(x, y)});
  }
  return r;
}

// z = -(A x^2 + B y^2) to second order: A = B = 1 / (2R) for a sphere of radius R.
TEST(Curvature, SphereOfKnownRadius) {
  for (double R : {0.05, 0.5, 20.0}) {
    const auto pts = ring(
        8, 0.05 * R, [&](double x, double y) { return -(R - std::sqrt(R * R - x * x - y * y)); });
    const glm::dvec2 ab = fit_quadric(pts);
    // Higher-order terms of the sphere at h = R / 20: relative error ~ h^2 / (4 R^2) < 0.1%.
    EXPECT_NEAR(ab.x, 1 / (2 * R), 1e-3 / (2 * R)) << "R=" << R;
    EXPECT_NEAR(ab.y, 1 / (2 * R), 1e-3 / (2 * R)) << "R=" << R;
  }
}

TEST(Curvature, CylinderOfKnownRadius) {
  // Axis along y: curved along x only.
  const double R = 0.3;
  const auto pts = ring(6, 0.02, [&](double x, double) { return -(R - std::sqrt(R * R - x * x)); });
  const glm::dvec2 ab = fit_quadric(pts);
  // The x^4 term of the circle leaks into both columns of the least squares: 0.1% of A.
  EXPECT_NEAR(ab.x, 1 / (2 * R), 1e-3 / (2 * R));
  EXPECT_NEAR(ab.y, 0.0, 1e-3 / (2 * R));
}

TEST(Curvature, DegenerateRingsGiveDefinedFiniteResults) {
  // Fewer than 3 neighbours: (0, 0), as Listing 5.8 returns.
  EXPECT_EQ(fit_quadric({}), glm::dvec2(0));
  EXPECT_EQ(fit_quadric({{0.1, 0, -0.01}, {0, 0.1, -0.02}}), glm::dvec2(0));
  // Collinear neighbours (all on the x axis): y^2 is never seen, so B is the minimum-norm 0.
  const glm::dvec2 line = fit_quadric({{0.1, 0, -0.01}, {-0.1, 0, -0.01}, {0.2, 0, -0.04}});
  EXPECT_NEAR(line.x, 1.0, 1e-9);
  EXPECT_EQ(line.y, 0.0);
  // Every neighbour on the vertex itself (a collapsed ring): zero, not NaN.
  const glm::dvec2 collapsed = fit_quadric({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}});
  EXPECT_EQ(collapsed, glm::dvec2(0));
  // Nearly collinear: huge but finite.
  const glm::dvec2 thin = fit_quadric({{0.1, 1e-9, -0.01}, {-0.1, 0, -0.01}, {0.2, -1e-9, -0.04}});
  EXPECT_TRUE(std::isfinite(thin.x) && std::isfinite(thin.y));
}

// Figure 5.28 checked where it has a closed form: the fitted (A, B) of every vertex against the
// sphere's and the torus's exact curvature. Ring points are chords of the surface, so the fit's
// error is second order in the edge length: it falls about fourfold per doubling of the
// segments (measured: sphere 2.36, 0.58, 0.14% mean at 24, 48, 96 segments; torus 7.3, 2.0,
// 0.52% mean, 20.9, 8.9, 3.6% at worst, on the tube's top where the ring coefficient is small).
// The signs Figure 5.28 colours are right on every vertex that is not planar there.
TEST(Curvature, FitErrorAgainstTheClosedFormFallsFourfoldPerDoubling) {
  for (const char* kind : {"sphere", "torus"}) {
    double previous = 0;
    for (int segments : {24, 48, 96}) {
      SCOPED_TRACE(std::string(kind) + " " + std::to_string(segments));
      const BaseDesc desc{kind, "", segments};
      const std::optional<CurvatureFitError> e =
          curvature_fit_error(desc, make_base_mesh(desc, 2.0, 1.0));
      ASSERT_TRUE(e.has_value());
      EXPECT_EQ(e->sign_match_pct, 100.0);
      EXPECT_LE(e->mean_pct, e->max_pct);
      EXPECT_LT(e->max_pct, std::string(kind) == "sphere" ? 3.0 : 21.0);
      if (previous > 0) {
        EXPECT_GT(previous / e->mean_pct, 3.5);
      }
      previous = e->mean_pct;
    }
  }
  // Every vertex wrong by a factor: the error says so.
  const BaseDesc torus{"torus", "", 48};
  BaseMesh scaled = make_base_mesh(torus, 1.0, 1.0);
  for (glm::dvec2& c : scaled.curvature) c *= 1.5;
  EXPECT_GT(curvature_fit_error(torus, scaled)->mean_pct, 40.0);
  for (glm::dvec2& c : scaled.curvature) c.x = -c.x;  // the ring direction's sign flipped
  EXPECT_LT(curvature_fit_error(torus, scaled)->sign_match_pct, 75.0);
  for (const char* other : {"plane", "cube", "teapot"})
    EXPECT_FALSE(curvature_fit_error(BaseDesc{other, "", 24},
                                     make_base_mesh(BaseDesc{other, "", 24}, 1.0, 1.0))
                     .has_value())
        << other;
}

TEST(Curvature, GeneratedSphereAndTorusMatchTheirRadii) {
  BaseDesc sphere{"sphere", "", 48};
  const BaseMesh s = make_base_mesh(sphere, 1.0, 1.0);
  int checked = 0;
  for (size_t i = 0; i < s.position.size(); ++i) {
    if (std::abs(s.normal[i].z) > 0.9) continue;  // near the poles the uv grid degenerates
    // Ring points are chord-connected: the fit sees the sphere's curvature within 2%.
    EXPECT_NEAR(s.curvature[i].x, 1.0, 0.02) << i;  // 1 / (2 R) with R = 0.5
    EXPECT_NEAR(s.curvature[i].y, 1.0, 0.02) << i;
    ++checked;
  }
  EXPECT_GT(checked, 500);

  // Torus: outside both directions convex; inside the tube a saddle (Figure 5.28).
  BaseDesc torus{"torus", "", 48};
  const BaseMesh t = make_base_mesh(torus, 1.0, 1.0);
  const double major = 0.35, minor = 0.15;
  int outside = 0, inside = 0;
  for (size_t i = 0; i < t.position.size(); ++i) {
    const double rho = std::hypot(t.position[i].x, t.position[i].y);
    if (std::abs(t.position[i].z) > 1e-9) continue;  // on the torus's equator only
    if (rho > major) {
      // Around the main circle 1 / (2 (R + r)), around the tube 1 / (2 r).
      EXPECT_NEAR(t.curvature[i].x, 1 / (2 * (major + minor)), 0.05 / (2 * (major + minor)));
      EXPECT_NEAR(t.curvature[i].y, 1 / (2 * minor), 0.05 / (2 * minor));
      ++outside;
    } else {
      EXPECT_LT(t.curvature[i].x, 0) << "inside the hole the main circle bends away";
      EXPECT_GT(t.curvature[i].y, 0);
      ++inside;
    }
  }
  EXPECT_GT(outside, 10);
  EXPECT_GT(inside, 10);
}

TEST(TangentFrames, MatchTheAnalyticSphereMapping) {
  // u = 2 tile turns around z, v = tile from pole to pole: |dP/du| = pi R sin(theta) / tile.
  const double R = 0.5, tile = 2;
  const BaseMesh m = make_base_mesh(BaseDesc{"sphere", "", 64}, 2 * R, tile);
  for (size_t i = 0; i < m.position.size(); ++i) {
    const glm::dvec3 n = m.normal[i];
    const double sin_theta = std::hypot(n.x, n.y);
    ASSERT_TRUE(std::isfinite(glm::length(m.dpdu[i])) && std::isfinite(glm::length(m.dpdv[i])));
    if (sin_theta < 0.3) continue;
    const glm::dvec3 analytic_u = glm::normalize(glm::dvec3(-n.y, n.x, 0));
    // The mesh sees chords of the neighbouring rings, angle-weighted: within 3.6 degrees and 2%
    // of the equator's scale.
    EXPECT_GT(glm::dot(glm::normalize(m.dpdu[i]), analytic_u), 0.998) << i;
    EXPECT_NEAR(glm::length(m.dpdu[i]), kPi * R * sin_theta / tile, 0.02 * kPi * R / tile) << i;
    EXPECT_NEAR(glm::length(m.dpdv[i]), kPi * R / tile, 0.02 * kPi * R / tile) << i;
    // An orthonormal frame with the normal, right-handed (T x B = N).
    EXPECT_NEAR(glm::dot(glm::cross(glm::normalize(m.dpdu[i]), glm::normalize(m.dpdv[i])), n), 1.0,
                1e-9);
  }
}

TEST(BaseMesh, TeapotGetsASeamlessCylindricalMapping) {
  const double tile = 1;
  const BaseMesh m = make_base_mesh(BaseDesc{"teapot", "", 32}, 1.0, tile);
  EXPECT_GT(m.triangles.size(), 900u);
  int off_axis = 0;
  for (const glm::uvec3& t : m.triangles) {
    double lo = 1e9, hi = -1e9, r = 1e9;
    for (int k = 0; k < 3; ++k) {
      lo = std::min(lo, m.uv[t[k]].x);
      hi = std::max(hi, m.uv[t[k]].x);
      r = std::min(r, std::hypot(m.position[t[k]].x, m.position[t[k]].y));
    }
    // Away from the axis a triangle covers a small angle; one crossing the seam unwrapped
    // wrongly would span most of a turn (2 tiles). Around the axis any angle is legitimate.
    if (r < 0.1) continue;
    ++off_axis;
    ASSERT_LT(hi - lo, 0.25 * tile) << "a triangle spans the seam";
  }
  EXPECT_GT(off_axis, 700);
  for (size_t i = 0; i < m.position.size(); ++i) {
    ASSERT_LE(glm::length(m.position[i]), 0.5 + 1e-9);
    ASSERT_GT(glm::length(m.dpdu[i]), 0.0);  // floored where the projection collapses
    ASSERT_TRUE(std::isfinite(m.curvature[i].x) && std::isfinite(m.curvature[i].y));
  }
}

TEST(BaseMesh, MeshFileWithoutUvsIsAClearError) {
  const std::string bunny = std::string(RELIEFLAB_SOURCE_DIR) + "/assets/meshes/bunny.obj";
  try {
    make_base_mesh(BaseDesc{"file", bunny, 32}, 1.0, 1.0);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("bunny.obj"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("texture coordinates"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make_base_mesh(BaseDesc{"cone", "", 32}, 1.0, 1.0), ConfigError);
}

}  // namespace
}  // namespace rl
