// The heightfield truth checked by code it does not share: closed-form scenes solved here, in
// long double, piece by piece, and a deliberately simple reference (fine uniform steps and
// bisection) on a real 1024^2 map. Nothing here calls the truth's walk, the reference walk of
// relief/heightfield_reference.h or core/grid_walk.h.
//
// Stated tolerance: hit/miss exact, positions within 0.01 texel, at every elevation
// from 1 to 90 degrees, on 1024^2 and 2048^2 maps (one non-square).
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "metrics/metrics.h"
#include "output/pareto.h"
#include "output/tables.h"
#include "scene/base_mesh.h"
#include "scene/relief_asset.h"
#include "support/test_support.h"
#include "truth/displaced_truth.h"
#include "truth/heightfield_truth.h"
#include "truth/truth_render.h"

namespace rl {
namespace {

using Real = long double;

// The default scene's proportions: relief depth 0.08 on a unit quad (texture units per depth
// unit sideways = 0.08 / tan(elevation)).
constexpr double kAspect = 0.08;
constexpr double kElevations[] = {1, 5, 20, 45, 90};

// A periodic, piecewise-linear profile in texel-centre coordinates (texel centre i at x = i):
// values at breakpoints, repeating every `period` texels. Linear between breakpoints, and the
// breakpoints lie on texel centres, so sampling it at the centres and interpolating bilinearly
// gives back the profile exactly.
struct Profile {
  std::vector<Real> at;     // breakpoint positions in [0, period), ascending, at[0] = 0
  std::vector<Real> value;  // the profile there
  Real period = 0;
  Real operator()(Real x) const {
    Real p = std::fmod(x, period);
    if (p < 0) p += period;
    for (size_t k = 0; k < at.size(); ++k) {
      const Real a = at[k], b = k + 1 < at.size() ? at[k + 1] : period;
      const Real va = value[k], vb = value[(k + 1) % value.size()];
      if (p <= b) return va + (vb - va) * (p - a) / (b - a);
    }
    return value[0];
  }
};

// Depth f(x, y) = base + gx * X(x) + gy * Y(y) + gxy * X(x) * Y(y): bilinear on every piece
// (a breakpoint interval of X times one of Y), so one quadratic in t per piece along a ray.
struct ClosedForm {
  Profile X, Y;
  Real base = 0, gx = 0, gy = 0, gxy = 0;
  Real depth(Real x, Real y) const {
    const Real a = X(x), b = Y(y);
    return base + gx * a + gy * b + gxy * a * b;
  }
};

// Breakpoints of a profile crossed by x0 + t dx for t in (t0, t1).
void crossings(const Profile& p, Real x0, Real dx, Real t0, Real t1, std::vector<Real>& out) {
  if (dx == 0) return;
  const Real lo = std::min(x0 + dx * t0, x0 + dx * t1), hi = std::max(x0 + dx * t0, x0 + dx * t1);
  const long first = long(std::floor(lo / p.period)) - 1,
             last = long(std::floor(hi / p.period)) + 1;
  for (long n = first; n <= last; ++n)
    for (Real a : p.at) {
      const Real x = a + Real(n) * p.period;
      if (x > lo && x < hi) out.push_back((x - x0) / dx);
    }
}

// The smallest root in [0, h] of c2 s^2 + c1 s + c0 (c0 < 0), or NaN.
Real first_root(Real c2, Real c1, Real c0, Real h) {
  Real best = NAN;
  auto take = [&](Real s) {
    if (s >= 0 && s <= h && !(s >= best)) best = s;
  };
  if (std::abs(c2) <= 1e-30L * (std::abs(c1) + std::abs(c0))) {
    if (c1 != 0) take(-c0 / c1);
    return best;
  }
  Real disc = c1 * c1 - 4 * c2 * c0;
  if (disc < 0) return best;
  const Real q = -0.5L * (c1 + std::copysign(std::sqrt(disc), c1));
  take(q / c2);
  if (q != 0) take(c0 / q);
  return best;
}

// The first t in [0, t_max] with ray depth >= f: piece by piece, where f along the ray is a
// quadratic in t (fitted through three points of the piece: exact for a quadratic) solved by
// the quadratic formula in long double. NaN if none.
Real closed_form_hit(const ClosedForm& s, const glm::dvec3& o, const glm::dvec3& d, Real t_max,
                     int width, int height) {
  const Real x0 = Real(o.x) * width - 0.5L, y0 = Real(o.y) * height - 0.5L;
  const Real dx = Real(d.x) * width, dy = Real(d.y) * height;
  std::vector<Real> ts = {0, t_max};
  crossings(s.X, x0, dx, 0, t_max, ts);
  crossings(s.Y, y0, dy, 0, t_max, ts);
  std::sort(ts.begin(), ts.end());
  auto g = [&](Real t) { return Real(o.z) + Real(d.z) * t - s.depth(x0 + dx * t, y0 + dy * t); };
  for (size_t k = 0; k + 1 < ts.size(); ++k) {
    const Real a = ts[k], b = ts[k + 1], h = b - a;
    if (!(h > 0)) continue;
    const Real ga = g(a), gm = g(a + h / 2), gb = g(b);
    if (ga >= 0) return a;
    const Real c2 = 2 * (gb - 2 * gm + ga) / (h * h), c1 = (4 * gm - 3 * ga - gb) / h;
    const Real root = first_root(c2, c1, ga, h);
    if (!std::isnan(root)) return a + root;
  }
  return NAN;
}

// The map of a closed form: its depth at every texel centre (dyadic values, exact in float).
ReliefMap closed_form_map(const ClosedForm& s, int width, int height) {
  // The profiles once per column and per row (ClosedForm::depth, term by term): a 2048^2 map
  // is 4M texels but only 4096 profile values.
  std::vector<Real> x(width), y(height);
  for (int i = 0; i < width; ++i) x[i] = s.X(i);
  for (int j = 0; j < height; ++j) y[j] = s.Y(j);
  std::vector<float> depths;
  depths.reserve(size_t(width) * height);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i)
      depths.push_back(float(s.base + s.gx * x[i] + s.gy * y[j] + s.gxy * x[i] * y[j]));
  return test::map_from_depths(width, height, depths);
}

// A triangle wave over `period` texels between lo and hi (tilted planes meeting in creases).
Profile triangle(Real period, Real lo, Real hi) {
  return {{0, period / 2}, {lo, hi}, period};
}
// One step per period: lo for half of it, hi for the other half (two one-texel ramps).
Profile step(Real period, Real lo, Real hi) {
  return {{0, 1, period / 2, period / 2 + 1}, {lo, hi, hi, lo}, period};
}
Profile flat() {
  return {{0}, {0}, 1};
}

// Tilted planes: a triangle wave across u, two planes sloping 0.6 depth units over a quarter
// of the map each way.
ClosedForm tilted_planes(int width) {
  ClosedForm s;
  s.X = triangle(width / 2, 0, 1);
  s.Y = flat();
  s.base = 0.25L;
  s.gx = 0.5L;
  return s;
}
// A bilinear saddle: depth 0.5 + 0.4 X Y with X, Y triangle waves in [-1, 1]: every piece a
// hyperbolic paraboloid, so each ray meets it where a quadratic with known roots vanishes.
ClosedForm saddle(int width, int height) {
  ClosedForm s;
  s.X = triangle(width / 4, -1, 1);
  s.Y = triangle(height / 4, -1, 1);
  s.base = 0.5L;
  s.gxy = 0.375L;
  return s;
}
// A single step across u from depth 0.875 to 0.125 over one texel, twice per map.
ClosedForm single_step(int width) {
  ClosedForm s;
  s.X = step(width / 2, 0, 1);
  s.Y = flat();
  s.base = 0.875L;
  s.gx = -0.75L;
  return s;
}

struct Agreement {
  long rays = 0, hit_miss = 0, over_001 = 0;
  double worst = 0;  // texels
};

// Rays from above the top at `elevation` in every direction, starting anywhere on the tile.
std::vector<test::TangentRay> rays_at(double elevation, int n, unsigned seed) {
  if (elevation >= 90) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<test::TangentRay> rays;
    for (int i = 0; i < n; ++i) rays.push_back({{u(rng), u(rng), -1e-3}, {0, 0, 1}});
    return rays;
  }
  return test::random_tangent_rays(n, elevation, elevation, kAspect, seed, -1e-3);
}

// A hit's distance from the expected one in texels: u and v in texels, depth in texels of the
// quad (kAspect depth units of world per texture unit).
double texel_distance(const glm::dvec3& d, Real dt, int width, int height) {
  const Real du = Real(d.x) * dt * width, dv = Real(d.y) * dt * height;
  const Real dz = Real(d.z) * dt * kAspect * width;
  return double(std::sqrt(du * du + dv * dv + dz * dz));
}

Agreement agree(const HeightfieldTruth& truth,
                const std::function<Real(const test::TangentRay&)>& expected,
                const std::vector<test::TangentRay>& rays, int width, int height) {
  Agreement a;
  for (const test::TangentRay& r : rays) {
    const TruthHit h = truth.intersect(r.origin, r.direction, 0, 1.5);
    const Real want = expected(r);
    ++a.rays;
    if (h.hit != !std::isnan(want)) {
      ++a.hit_miss;
      continue;
    }
    if (!h.hit) continue;
    const double off = texel_distance(r.direction, Real(h.t) - want, width, height);
    a.worst = std::max(a.worst, off);
    a.over_001 += off > 0.01;
  }
  return a;
}

TEST(TruthExact, ClosedFormScenesAtEveryElevationAndSize) {
  struct Size {
    int width, height;
  };
  for (const Size size : {Size{1024, 1024}, Size{2048, 2048}, Size{2048, 512}}) {
    const std::vector<std::pair<const char*, ClosedForm>> scenes = {
        {"tilted planes", tilted_planes(size.width)},
        {"saddle", saddle(size.width, size.height)},
        {"single step", single_step(size.width)}};
    for (const auto& [name, form] : scenes) {
      const ReliefMap map = closed_form_map(form, size.width, size.height);
      const HeightfieldTruth truth(map);
      for (double elevation : kElevations) {
        const auto rays = rays_at(elevation, 150, unsigned(elevation) + 7);
        const Agreement a = agree(
            truth,
            [&](const test::TangentRay& r) {
              return closed_form_hit(form, r.origin, r.direction, 1.5, size.width, size.height);
            },
            rays, size.width, size.height);
        SCOPED_TRACE(std::string(name) + " at " + std::to_string(size.width) + "x" +
                     std::to_string(size.height) + ", " + std::to_string(elevation) + " deg");
        EXPECT_EQ(a.hit_miss, 0);
        EXPECT_EQ(a.over_001, 0) << "worst " << a.worst << " texels";
      }
    }
  }
}

// The simple reference: the bilinear surface sampled at steps of 1/64 texel along the ray, in
// long double, the first step at or below it bisected 64 times. It can miss a feature thinner
// than a step; it cannot misplace one it finds.
Real stepped_hit(const ReliefMap& m, const glm::dvec3& o, const glm::dvec3& d, Real t_max) {
  auto texel = [&](long i, long j) {
    return Real(m.depth_texel(int(((i % m.width) + m.width) % m.width),
                              int(((j % m.height) + m.height) % m.height)));
  };
  auto surface = [&](Real u, Real v) {
    const Real x = u * m.width - 0.5L, y = v * m.height - 0.5L;
    const long i = long(std::floor(x)), j = long(std::floor(y));
    const Real fx = x - i, fy = y - j;
    return (1 - fx) * (1 - fy) * texel(i, j) + fx * (1 - fy) * texel(i + 1, j) +
           (1 - fx) * fy * texel(i, j + 1) + fx * fy * texel(i + 1, j + 1);
  };
  auto below = [&](Real t) {
    return Real(o.z) + Real(d.z) * t >=
           surface(Real(o.x) + Real(d.x) * t, Real(o.y) + Real(d.y) * t);
  };
  const Real lateral = std::abs(Real(d.x)) * m.width + std::abs(Real(d.y)) * m.height;
  const Real step = std::min<Real>(1.0L / (64 * std::max<Real>(lateral, 1e-9L)), 1e-3L);
  Real previous = 0;
  if (below(0)) return 0;
  for (Real t = step; t <= t_max + step; t += step) {
    const Real at = std::min(t, t_max);
    if (below(at)) {
      Real a = previous, b = at;
      for (int k = 0; k < 64; ++k) ((below((a + b) / 2)) ? b : a) = (a + b) / 2;
      return b;
    }
    previous = at;
    if (at >= t_max) break;
  }
  return NAN;
}

TEST(TruthExact, AgreesWithSteppingAndBisectionOnARealMapAtFiveDegrees) {
  SceneDesc scene;
  scene.name = "panel";
  scene.relief.normal_path =
      std::string(RELIEFLAB_TEST_DIR) + "/../assets/relief/trak5/panel1_n.png";
  scene.relief.normalize = true;
  scene.relief.native = {512, 512};
  scene.quantize = true;
  const ReliefMap map = build_relief_asset(scene, 1024);
  ASSERT_EQ(map.width, 1024);
  const HeightfieldTruth truth(map);
  const auto rays = test::random_tangent_rays(300, 5, 5, kAspect, 5, -1e-3);
  const Agreement a = agree(
      truth,
      [&](const test::TangentRay& r) { return stepped_hit(map, r.origin, r.direction, 1.5); }, rays,
      map.width, map.height);
  EXPECT_EQ(a.hit_miss, 0);
  EXPECT_LE(a.worst, 0.01);  // every ray: the reference's bisection is exact to 2^-64 of a step
}

// Every truth G-buffer states its bound per pixel; the row's columns follow from it. The exact
// heightfield truth stays far below the target at 1 degree on a 1024^2 map.
TEST(TruthBound, TheExactTruthStatesATexelBoundWellBelowTheTargetAtOneDegree) {
  SceneDesc scene = test::procedural_scene("bricks", 1024, 0.08, true);
  apply_fill_framing(scene, 1.0, 1.0);
  const ReliefMap map = build_relief_asset(scene, 1024);
  const HeightfieldTruth truth(map);
  const GBuffer g = render_truth(truth, map, scene, make_camera(scene, View{1, 30}, 64, 64), {});
  const double texel = planar_base(scene).texel_world(map.width);
  const ImageMetrics m = compare_gbuffers(g, g, scene.depth, texel);
  EXPECT_GT(m.at("truth_bound_texels"), 0.0);  // stated: the float storage of positions at least
  EXPECT_LE(m.at("truth_bound_texels"), kTruthBoundTarget);
  EXPECT_EQ(m.at("truth_uncertain_pct"), 0.0);
  EXPECT_FALSE(m.truth_flagged());
}

// The displaced-mesh truth (the curved bases' path) checked against a closed form: a flat base
// mesh drawn through it, carrying the saddle. Wherever its hit lies inside the quad, the
// closed-form hit is within the truth's own stated per-pixel bound (first order: 99.5% of the
// pixels asked for; a ray tangent to the saddle may exceed it).
TEST(TruthBound, TheDisplacedTruthsStatedBoundHoldsAgainstAClosedForm) {
  const int size = 128;
  const SceneDesc scene = test::procedural_scene("flat", size, 0.08);
  const ClosedForm form = saddle(size, size);
  const ReliefMap map = closed_form_map(form, size, size);
  const DisplacedTruth truth(make_base_mesh(BaseDesc{"plane", "", 1}, scene.size, scene.tile), map,
                             scene.depth);
  const PlanarBase base = planar_base(scene);
  for (double elevation : {5.0, 20.0, 45.0, 90.0}) {
    const Camera camera = make_camera(scene, View{elevation, 30}, 96, 96);
    const GBuffer g = render_truth(truth, map, scene, camera, {});
    long inside = 0, within = 0;
    for (size_t i = 0; i < g.size(); ++i) {
      if (!g.covered(i)) continue;
      glm::dvec3 eye, dir;
      camera.pixel_ray(int(i % camera.width), int(i / camera.width), eye, dir);
      const glm::dvec3 o = base.texture_from_world(eye), d = base.texture_direction(dir);
      const double t_top = -o.z / d.z;
      const glm::dvec3 entry = o + d * t_top;
      const Real t = closed_form_hit(form, entry, d, 1.5 / d.z, size, size);
      if (std::isnan(t)) continue;
      const glm::dvec3 hit = entry + d * double(t);
      if (hit.x < 0.02 || hit.y < 0.02 || hit.x > 0.98 || hit.y > 0.98) continue;  // sheet's edge
      ++inside;
      const glm::dvec3 exact = eye + dir * (t_top + double(t));
      within += glm::distance(exact, glm::dvec3(g.position[i])) <= double(g.aux[i].w) + 1e-6;
    }
    EXPECT_GT(inside, 400) << elevation;  // at 5 degrees the fitted view sees the quad edge-on
    EXPECT_GE(within, inside * 995 / 1000) << within << " of " << inside << " at " << elevation;
  }
}

// A value resting on a flagged row is marked, explained and never the column's best.
TEST(TruthBound, FlaggedRowsAreMarkedInTheTables) {
  std::vector<Row> rows(2);
  rows[0]["technique"] = "a";
  rows[0]["wrong_pct"] = 0.5;
  rows[0]["truth_flagged"] = true;
  rows[1]["technique"] = "b";
  rows[1]["wrong_pct"] = 1.5;
  rows[1]["truth_flagged"] = false;
  rows[0]["fetches_mean"] = 12.0;  // a cost: the truth does not enter it, so it is not marked
  rows[1]["fetches_mean"] = 14.0;
  rows[0]["ao_err_mean"] = nullptr;  // nothing measured: nothing to mark
  rows[1]["ao_err_mean"] = nullptr;
  TableSpec spec;
  spec.rows = {"technique"};
  spec.values = {"wrong_pct", "fetches_mean", "ao_err_mean"};
  const std::string md = format_markdown_table(rows, spec);
  EXPECT_NE(md.find("| a | 0.5 " + std::string(kTruthFlagMark) + " | 12 | – |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| b | 1.5 | 14 | – |"), std::string::npos) << md;
  EXPECT_NE(md.find(truth_flag_note()), std::string::npos) << md;
  const std::string tex = format_latex_table(rows, spec);
  EXPECT_NE(tex.find("0.5$^\\dagger$"), std::string::npos) << tex;
  EXPECT_NE(tex.find("\\textbf{1.5}"), std::string::npos) << tex;  // the best unflagged value
}

// A flagged setting is drawn but not ranked: it neither sits on the front nor pushes a setting
// it would beat off it.
TEST(TruthBound, FlaggedSettingsAreNotRankedOnTheParetoFront) {
  std::vector<Row> rows(2);
  rows[0]["technique"] = "a";
  rows[0]["gpu_frame_ms"] = 5.0;  // the default plot's cost
  rows[0]["wrong_pct"] = 0.5;
  rows[0]["truth_flagged"] = true;
  rows[1]["technique"] = "b";
  rows[1]["gpu_frame_ms"] = 10.0;
  rows[1]["wrong_pct"] = 1.5;
  rows[1]["truth_flagged"] = false;
  const std::vector<PlotGroup> groups = plot_groups(rows, PlotSpec{}, {});
  ASSERT_EQ(groups.size(), 1u);
  ASSERT_EQ(groups[0].points.size(), 2u);
  EXPECT_TRUE(groups[0].points[0].flagged);
  EXPECT_EQ(pareto_front(groups[0].points), std::vector<size_t>{1});
}

}  // namespace
}  // namespace rl
