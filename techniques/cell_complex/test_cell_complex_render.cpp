// The cell-complex techniques on the GPU (Apaza & Andujar, Sections 3.5.1-3.5.2): the ray
// caster's search against the CPU's encoded surface (probe rays crossing cells of different
// projection types, grazing cell faces, on grids from 1 to the cap), whole frames against the
// mesh and the encoded surface, and the hard cases of construction drawn finitely.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>

#include "gl/context.h"
#include "gpu/gpu_scene.h"
#include "relief/cell_complex.h"
#include "scene/relief_asset.h"
#include "support/test_support.h"
#include "truth/cell_complex_truth.h"

namespace rl {
namespace {

// An axis-aligned box [lo, hi]^3, counter-clockwise from outside.
TriangleMesh box(double lo, double hi) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.push_back(glm::vec3(i & 1 ? hi : lo, i & 2 ? hi : lo, i & 4 ? hi : lo));
  const unsigned q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                            {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : q) {
    m.triangles.push_back({f[0], f[1], f[2]});
    m.triangles.push_back({f[0], f[2], f[3]});
  }
  m.lo = glm::dvec3(lo);
  m.hi = glm::dvec3(hi);
  return m;
}

struct Probed {
  std::vector<ProbeHit> gpu;
  std::vector<TruthHit> cpu;
};

// Probe rays from the cube's boundary inward, searched by the GPU technique (the whole chord)
// and by the CPU's encoded-surface truth.
Probed probe(const CellComplex& cc, const std::vector<ProbeRay>& rays, int steps_per_cell) {
  GlContext::shared();
  ReliefMap map;
  map.width = map.height = 2;
  map.relief.assign(4, glm::vec4(0.5f, 0.5f, 1.0f, 0.0f));
  map.color.assign(4, glm::vec4(1.0f));
  map.cells = std::make_shared<const CellComplex>(cc);
  GpuRelief relief(map);
  auto t = TechniqueRegistry::instance().create(
      "cell_complex", {{"steps_per_cell", double(steps_per_cell)}, {"binary_steps", 12}}, "test");
  t->prepare(map);
  Probed p;
  p.gpu = t->probe(map, relief, rays, glm::dvec2(1));
  const CellComplexTruth truth(map.cells);
  for (const ProbeRay& r : rays) p.cpu.push_back(truth.intersect(r.origin, r.direction, 0, 2));
  return p;
}

// Rays entering the cube through a random point of its boundary, towards a random point inside
// (unit directions, so t is in cube sides).
std::vector<ProbeRay> inward_rays(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::vector<ProbeRay> rays;
  for (int i = 0; i < n; ++i) {
    glm::dvec3 o(u01(rng), u01(rng), u01(rng));
    const int axis = int(u01(rng) * 3) % 3;
    o[axis] = u01(rng) < 0.5 ? 0.0 : 1.0;
    const glm::dvec3 target(0.15 + 0.7 * u01(rng), 0.15 + 0.7 * u01(rng), 0.15 + 0.7 * u01(rng));
    rays.push_back({glm::vec3(o), glm::vec3(glm::normalize(target - o)), glm::vec2(0)});
  }
  return rays;
}

// The search's bound: the grid's longest chord in steps, its binary steps, a table and a
// distance fetch each.
int fetch_bound(int n, int steps, int binary) {
  return 2 * (int(std::ceil(std::sqrt(3.0) * n * steps)) + 2 + binary);
}

void expect_agreement(const CellComplex& cc, const std::vector<ProbeRay>& rays, int steps,
                      double max_disagree_pct) {
  const Probed p = probe(cc, rays, steps);
  const double texel = 1.0 / (cc.grid() * cc.resolution());
  int disagree = 0, both = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const ProbeHit& g = p.gpu[i];
    ASSERT_TRUE(std::isfinite(g.t) && std::isfinite(g.uv.x) && std::isfinite(g.depth)) << i;
    EXPECT_LE(g.fetches, fetch_bound(cc.grid(), steps, 12)) << i;
    if (g.hit != p.cpu[i].hit) {
      ++disagree;
      continue;
    }
    if (!g.hit) continue;
    ++both;
    // Within two texels of the encoded surface's first crossing along the ray.
    if (std::abs(double(g.t) - p.cpu[i].t) > 2 * texel) ++disagree;
  }
  EXPECT_GT(both, int(rays.size()) / 5);
  EXPECT_LE(100.0 * disagree / rays.size(), max_disagree_pct)
      << disagree << " of " << rays.size() << " rays";
}

// An axis-aligned box [lo, hi] (per axis), counter-clockwise from outside, appended to `m`.
void add_box(TriangleMesh& m, glm::vec3 lo, glm::vec3 hi) {
  const unsigned k = unsigned(m.positions.size());
  for (int i = 0; i < 8; ++i)
    m.positions.push_back(glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z));
  const unsigned q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                            {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : q) {
    m.triangles.push_back({k + f[0], k + f[1], k + f[2]});
    m.triangles.push_back({k + f[0], k + f[2], k + f[3]});
  }
  m.lo = glm::min(m.lo, glm::dvec3(lo));
  m.hi = glm::max(m.hi, glm::dvec3(hi));
}

TEST(CellComplexProbe, TheRayCasterFindsTheEncodedSurfaceAcrossProjectionTypes) {
  // A sphere on 1, 4 and 8 cells per side (perspective and parallel cells), and on 8 cells a
  // rod one cell thick (axial cells, case 2b) beside a slab one cell thick (planar cells, case
  // 4a): rays cross cells of different projection types. A wrong projection, face index or
  // tile in the shader moves its hits off the CPU's.
  const TriangleMesh sphere = test::uv_sphere({0.5, 0.5, 0.5}, 0.37, 96, 48);
  TriangleMesh rod_and_slab;
  rod_and_slab.lo = glm::dvec3(1);
  rod_and_slab.hi = glm::dvec3(0);
  add_box(rod_and_slab, {0.1f, 0.39f, 0.39f}, {0.9f, 0.49f, 0.49f});
  add_box(rod_and_slab, {0.1f, 0.1f, 0.64f}, {0.9f, 0.9f, 0.74f});
  const std::vector<ProbeRay> rays = inward_rays(3000, 3);
  for (int n : {1, 4, 8}) {
    SCOPED_TRACE("sphere, N " + std::to_string(n));
    expect_agreement(CellComplex::build(sphere, {.grid = n, .resolution = 32}), rays, 64, 0.5);
  }
  SCOPED_TRACE("rod and slab, N 8");
  const CellComplex cc = CellComplex::build(rod_and_slab, {.grid = 8, .resolution = 32});
  std::set<CellProjection::Type> types;
  for (const auto& c : cc.cells())
    if (c.state == CellState::Grey) types.insert(c.config.projection.type);
  EXPECT_GE(types.size(), 3u);  // and the sphere has parallel (case 5) cells
  EXPECT_GT(cc.stats().cases[int(CellCase::C2b)], 0);
  EXPECT_GT(cc.stats().cases[int(CellCase::C4a)], 0);
  expect_agreement(cc, rays, 64, 1.0);
}

TEST(CellComplexProbe, RaysAlongGridPlanesAndAMeshOnThem) {
  // A box whose faces lie exactly on grid planes (N = 4: 0.25 and 0.75), and rays that run
  // inside the grid planes (grazing every cell face they pass): finite, bounded, and agreeing
  // with the CPU.
  const CellComplex cc = CellComplex::build(box(0.25, 0.75), {.grid = 4, .resolution = 16});
  EXPECT_EQ(cc.stats().black_cells, 0);  // every cell the box touches is grey (closed boxes)
  std::vector<ProbeRay> rays = inward_rays(1000, 5);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int i = 0; i < 300; ++i) {
    const double plane = 0.25 * (1 + i % 3);  // 0.25, 0.5, 0.75
    const double a = 2 * M_PI * u01(rng);
    rays.push_back({glm::vec3(0.0f, float(0.2 + 0.6 * u01(rng)), float(plane)),
                    glm::vec3(float(std::abs(std::cos(a)) + 0.1), float(0.3 * std::sin(a)), 0.0f),
                    glm::vec2(0)});
  }
  for (ProbeRay& r : rays) r.direction = glm::normalize(r.direction);
  expect_agreement(cc, rays, 64, 2.0);
}

TEST(CellComplexProbe, OneCellAndTheCapStayBounded) {
  const TriangleMesh sphere = test::uv_sphere({0.5, 0.5, 0.5}, 0.37, 48, 24);
  const std::vector<ProbeRay> rays = inward_rays(500, 13);
  for (int n : {1, kMaxCellGrid}) {
    SCOPED_TRACE("N " + std::to_string(n));
    const CellComplex cc = CellComplex::build(sphere, {.grid = n, .resolution = 8});
    expect_agreement(cc, rays, 16, 2.0);
  }
}

TEST(CellComplexBuildHardCases, DegenerateTrianglesAndHolesGiveDefinedResults) {
  TriangleMesh sphere = test::uv_sphere({0.5, 0.5, 0.5}, 0.37, 48, 24);
  const CellComplex clean = CellComplex::build(sphere, {.grid = 4, .resolution = 16});
  // Zero-area triangles (a repeated vertex, three collinear points) are skipped and counted.
  TriangleMesh degenerate = sphere;
  degenerate.positions.push_back({0.2f, 0.2f, 0.2f});
  degenerate.positions.push_back({0.4f, 0.4f, 0.4f});
  degenerate.positions.push_back({0.6f, 0.6f, 0.6f});
  const unsigned k = unsigned(degenerate.positions.size());
  degenerate.triangles.push_back({k - 3, k - 2, k - 1});
  degenerate.triangles.push_back({0, 0, 1});
  const CellComplex d = CellComplex::build(degenerate, {.grid = 4, .resolution = 16});
  EXPECT_EQ(d.stats().degenerate_triangles, 2);
  for (size_t i = 0; i < clean.cells().size(); ++i)
    EXPECT_EQ(d.cells()[i].state, clean.cells()[i].state) << i;
  // A hole wider than a cell: the inside joins the outside through it, so no cell is black
  // and the sphere is a shell; outputs stay finite and searches bounded.
  TriangleMesh open = sphere;
  std::vector<glm::uvec3> kept;
  for (const glm::uvec3& t : open.triangles)
    if (open.positions[t.x].z < 0.7f) kept.push_back(t);  // the cap above z = 0.7 removed
  open.triangles = kept;
  const CellComplex o = CellComplex::build(open, {.grid = 4, .resolution = 16});
  EXPECT_EQ(o.stats().black_cells, 0);
  expect_agreement(o, inward_rays(500, 17), 32, 2.0);
}

TEST(CellComplexBuildHardCases, SheetsBehindAFirstCrossingAreLostAndMeasured) {
  // A hollow ball (outer radius 0.4, inner 0.2): on one cell every line from the faces to the
  // centre crosses both spheres, so the hollow is filled (the inner sheet is lost, 50% of the
  // fragments occluded); on 8 cells the sheets fall in different cells and the hollow is kept.
  const TriangleMesh shell = test::hollow_ball();
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u01(-1.0, 1.0);
  auto hollow_kept_pct = [&](const CellComplex& cc) {
    int inside_hollow = 0, kept = 0;
    while (inside_hollow < 2000) {
      const glm::dvec3 p = glm::dvec3(0.5) + 0.17 * glm::dvec3(u01(rng), u01(rng), u01(rng));
      if (glm::length(p - glm::dvec3(0.5)) > 0.17) continue;
      ++inside_hollow;
      kept += !cc.encoded_inside(p);
    }
    return 100.0 * kept / inside_hollow;
  };
  const CellComplex one = CellComplex::build(shell, {.grid = 1, .resolution = 32});
  const CellComplex eight = CellComplex::build(shell, {.grid = 8, .resolution = 32});
  EXPECT_LT(hollow_kept_pct(one), 1.0);
  EXPECT_GT(hollow_kept_pct(eight), 99.0);
  EXPECT_GT(one.stats().occluded_ratio(), 10 * eight.stats().occluded_ratio());
}

// A sphere OBJ in a scratch folder, for whole-frame scenes.
std::string sphere_file(const std::string& dir) {
  return test::write_obj(test::uv_sphere({0, 0, 0}, 1, 64, 32), dir + "/sphere.obj");
}

SceneDesc cells_scene(const std::string& mesh, int grid, TruthLevel truth);

TEST(CellComplexAsset, ASecondBuildReadsTheCacheAndAnotherOptionDoesNot) {
  const std::string dir = test::scratch_dir("cell_cache");
  const std::string mesh = sphere_file(dir + "/mesh");
  ::setenv("RELIEFLAB_CACHE_DIR", (dir + "/cache").c_str(), 1);
  SceneDesc scene = cells_scene(mesh, 4, TruthLevel::Mesh);
  const ReliefMap first = build_relief_asset(scene, 16);
  const ReliefMap second = build_relief_asset(scene, 16);
  scene.relief.cells.distance_bits = 8;
  const ReliefMap other = build_relief_asset(scene, 16);
  ::unsetenv("RELIEFLAB_CACHE_DIR");
  EXPECT_FALSE(first.cells->stats().from_cache);
  EXPECT_TRUE(second.cells->stats().from_cache);
  EXPECT_FALSE(other.cells->stats().from_cache);
  EXPECT_EQ(second.cells->distance(), first.cells->distance());
  EXPECT_EQ(second.cells->stats().sample_ms, first.cells->stats().sample_ms);  // the build's
  EXPECT_EQ(second.cells->mesh().triangles.size(), first.cells->mesh().triangles.size());
}

SceneDesc cells_scene(const std::string& mesh, int grid, TruthLevel truth) {
  SceneDesc s;
  s.name = "cells";
  s.relief.mesh_path = mesh;
  s.relief.cells.active = true;
  s.relief.cells.grid = grid;
  s.relief.native = {32, 32};
  s.proxy = Proxy::Box;
  s.empty_floor = true;
  s.truth = truth;
  s.depth = s.size;
  return s;
}

TEST(CellComplexFrames, EveryCellTechniqueAgainstTheMeshAndTheEncodedSurface) {
  // Whole frames from above, at a grazing 3 degrees and from below: the mesh baseline is the
  // mesh; the ray caster is close to the surface its maps encode and to the sphere; the
  // geometry renderer covers it. All outputs finite.
  const std::string mesh = sphere_file(test::scratch_dir("cell_frames"));
  for (const View& view : {View{35, 20}, View{3, 100}, View{-40, 250}}) {
    SCOPED_TRACE("elevation " + std::to_string(view.elevation_deg));
    const SceneDesc on_mesh = cells_scene(mesh, 4, TruthLevel::Mesh);
    const SceneDesc encoded = cells_scene(mesh, 4, TruthLevel::Cells);
    for (const std::string& name : TechniqueRegistry::instance().names()) {
      const TechniqueInfo& info = TechniqueRegistry::instance().find(name)->info;
      if (!cannot_render(info, on_mesh).empty()) continue;
      SCOPED_TRACE(name);
      const test::Measured m = test::measure(on_mesh, name, {}, view, 96);
      EXPECT_EQ(m.metrics.at("nonfinite_px"), 0);
      EXPECT_GT(m.metrics.at("covered_px"), 1500);
      EXPECT_LT(m.metrics.at("wrong_pct"), name == "cell_source_mesh" ? 0.5 : 6.0);
    }
    const test::Measured e =
        test::measure(encoded, "cell_complex", {{"steps_per_cell", 32}}, view, 96);
    EXPECT_LT(e.metrics.at("wrong_pct"), 1.5);
    EXPECT_LT(e.metrics.at("missed_pct") + e.metrics.at("false_pct"), 1.0);
  }
}

}  // namespace
}  // namespace rl

namespace rl {
namespace {

TEST(CellComplexFrames, AnObjectThroughTheMeshResolvesPerPixel) {
  // Chapter 5's interpenetration test on a cell complex: a plain sphere half inside the cube's
  // mesh. The cell techniques write their hit's depth, so the object and the surface hide each
  // other where the truth says (object_disagree_pct), as the rasterised mesh does exactly.
  const std::string mesh = sphere_file(test::scratch_dir("cell_objects"));
  SceneDesc scene = cells_scene(mesh, 4, TruthLevel::Mesh);
  scene.objects.push_back({"sphere", {0.35, 0.0, -0.5}, 0.25, {0.85, 0.35, 0.2}});
  scene.effects.add(Effect::DepthCorrect);
  const test::Measured cast =
      test::measure(scene, "cell_complex", {{"steps_per_cell", 32}}, View{30, 30}, 96);
  const test::Measured raster = test::measure(scene, "cell_source_mesh", {}, View{30, 30}, 96);
  EXPECT_GT(cast.metrics.at("covered_px"), 2000);
  EXPECT_LT(cast.metrics.at("object_disagree_pct"), 0.5);
  EXPECT_LT(raster.metrics.at("object_disagree_pct"), 0.05);
  EXPECT_EQ(cast.metrics.at("nonfinite_px"), 0);
}

}  // namespace
}  // namespace rl
