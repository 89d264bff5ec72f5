#include "contract/contract_cases.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <tuple>

#include "core/error.h"
#include "gl/context.h"
#include "gl/op_count_buffer.h"
#include "gl/render_target.h"
#include "gl/shader_library.h"
#include "gpu/gpu_scene.h"
#include "relief/cell_complex.h"
#include "relief/heightfield_faces.h"
#include "relief/heightfield_reference.h"
#include "relief/procedural.h"
#include "scene/base_mesh.h"
#include "scene/relief_asset.h"
#include "support/test_support.h"
#include "truth/make_truth.h"

namespace rl::contract {

namespace {

ReliefMap map_of(int w, int h, const std::function<float(double, double)>& depth_at) {
  std::vector<float> d;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) d.push_back(depth_at((x + 0.5) / w, (y + 0.5) / h));
  return test::map_from_depths(w, h, d);
}

}  // namespace

const std::vector<ProbeMap>& probe_maps() {
  static const std::vector<ProbeMap> maps = [] {
    std::vector<ProbeMap> m;
    // Within a tile both planes are exact for bilinear cells; across the seam they jump.
    m.push_back({"tilted_u", map_of(64, 64, [](double u, double) { return 0.1 + 0.8 * u; }), true});
    m.push_back({"tilted_strip",
                 map_of(128, 32, [](double u, double v) { return 0.2 + 0.3 * u + 0.4 * v; }),
                 true});
    // (2u - 1)(2v - 1) is bilinear: every cell reproduces it exactly.
    m.push_back(
        {"saddle",
         map_of(64, 64, [](double u, double v) { return 0.5 + 0.45 * (2 * u - 1) * (2 * v - 1); }),
         true});
    m.push_back(
        {"sines", make_procedural("sines", 64, {{"frequency", 2}}, 10.0, "contract"), true});
    m.push_back(
        {"bricks_full_joints",
         make_procedural("bricks", 64,
                         {{"mortar_depth", 1.0}, {"rows", 4}, {"columns", 2}, {"mortar", 0.1}},
                         10.0, "contract"),
         false});
    // One-texel pillars rising from the floor to the top.
    m.push_back({"spikes",
                 map_of(64, 64,
                        [](double u, double v) {
                          const int x = int(u * 64), y = int(v * 64);
                          return (x % 8 == 3 && y % 8 == 5) ? 0.0f : 1.0f;
                        }),
                 false});
    m.push_back({"flat_top", map_of(64, 64, [](double, double) { return 0.0f; }), true});
    m.push_back({"empty", map_of(64, 64, [](double, double) { return 1.0f; }), true});
    return m;
  }();
  return maps;
}

std::vector<ProbeRay> hard_rays(bool from_inside) {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> anywhere(-1, 2), unit(0, 1), azimuth(0, 360);
  std::vector<ProbeRay> rays;
  for (double el : {1.0, 2.0, 5.0, 10.0, 20.0, 45.0, 70.0, 89.9, 90.0}) {
    const double lateral = el >= 90 ? 0 : kProbeAspect / std::tan(glm::radians(el));
    for (int i = 0; i < 48; ++i) {
      // Axes and diagonals first (degenerate steps of a walk), then any azimuth.
      const double az = glm::radians(i < 8 ? 45.0 * i : azimuth(rng));
      glm::dvec2 origin(anywhere(rng), anywhere(rng));
      if (i % 4 == 1) origin.x = std::round(origin.x);  // on a texture border / tiling seam
      if (i % 4 == 2) origin = glm::round(origin);      // on a corner of the tiles
      const double inside = 0.5 * unit(rng);
      const double z = from_inside && i % 8 == 7 ? inside : 0.0;
      rays.push_back({glm::vec3(glm::dvec3(origin, z)),
                      glm::vec3(float(lateral * std::cos(az)), float(lateral * std::sin(az)), 1)});
    }
  }
  return rays;
}

std::vector<ProbeRay> curved_rays() {
  std::vector<ProbeRay> rays = hard_rays(false);
  for (size_t i = 0; i < rays.size(); ++i)
    rays[i].quadric = glm::vec2(i % 2 ? 0.5f : 2.0f, i % 3 ? 1.0f : -0.5f);
  return rays;
}

ReferenceAnswer reference(const ReliefMap& map, const ProbeRay& ray, Surface surface) {
  const glm::dvec3 o(ray.origin), d(ray.direction);
  if (surface == Surface::Bilinear) {
    const ReferenceHit h = intersect_heightfield(map, o, d, 1.0 - o.z);
    return {h.hit, h.t, h.hit, h.t};
  }
  // Either side of a boundary the ray may run along, a millionth of a texel away.
  const glm::dvec3 nudge(1e-6 / map.width, 1e-6 / map.height, 0);
  const ReferenceHit a = intersect_texel_columns(map, o + nudge, d, 1.0 - o.z);
  const ReferenceHit b = intersect_texel_columns(map, o - nudge, d, 1.0 - o.z);
  return {a.hit, a.t, b.hit, b.t};
}

double surface_depth(const ReliefMap& map, Surface surface, double u, double v) {
  if (surface == Surface::Bilinear) return map.sample_depth(u, v);
  return map.depth_texel(int(std::floor(u * map.width)), int(std::floor(v * map.height)));
}

double inside_stretch(const ReliefMap& map, Surface surface, const ProbeRay& ray, double t_hit,
                      double up_to) {
  const glm::dvec3 o(ray.origin), d(ray.direction);
  const double ray_texels = glm::length(glm::dvec2(d) * glm::dvec2(map.width, map.height));
  // Samples a quarter texel apart along the ray (and at least 64 across the stretch).
  const double dt = std::min(up_to / 64, 0.25 / std::max(ray_texels, 1e-9));
  for (double t = t_hit + dt; t < t_hit + up_to; t += dt) {
    const glm::dvec3 p = o + t * d;
    if (p.z >= 1) return up_to;
    if (p.z < surface_depth(map, surface, p.x, p.y)) return t - t_hit;
  }
  return up_to;
}

RayQuery ray_query(const ParamValues& params, const ReliefMap& map, const ProbeRay& ray) {
  RayQuery q{.params = params, .map_width = map.width, .map_height = map.height};
  q.layer_groups = std::max(1, (map.layers.count + 3) / 4);
  q.span_texels = glm::abs(glm::dvec2(ray.direction)) * glm::dvec2(map.width, map.height);
  return q;
}

double texel_distance(const ReliefMap& map, glm::dvec3 a, glm::dvec3 b) {
  const glm::dvec3 d = b - a;
  return std::sqrt(std::pow(d.x * map.width, 2) + std::pow(d.y * map.height, 2) +
                   std::pow(d.z * kProbeAspect * map.width, 2));
}

double filtering_tolerance(const ReliefMap& map) {
  double jump = 0;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x)
      jump = std::max({jump, double(std::abs(map.depth_texel(x, y) - map.depth_texel(x + 1, y))),
                       double(std::abs(map.depth_texel(x, y) - map.depth_texel(x, y + 1)))});
  return jump / 256 + 1e-5;
}

double filtering_tolerance_at(const ReliefMap& map, double u, double v) {
  const int x0 = int(std::floor(u * map.width - 0.5)), y0 = int(std::floor(v * map.height - 0.5));
  float lo = 1, hi = 0;
  for (int y = y0 - 1; y <= y0 + 2; ++y)
    for (int x = x0 - 1; x <= x0 + 2; ++x) {
      lo = std::min(lo, map.depth_texel(x, y));
      hi = std::max(hi, map.depth_texel(x, y));
    }
  return (hi - lo) / 256 + 1e-5;
}

double depth_error_along_ray(const ReliefMap& map, const ProbeRay& ray, double t_hit,
                             double depth_error) {
  const glm::dvec3 p = glm::dvec3(ray.origin) + t_hit * glm::dvec3(ray.direction);
  const double du = 0.25 / map.width, dv = 0.25 / map.height;
  const glm::dvec2 gradient(
      (map.sample_depth(p.x + du, p.y) - map.sample_depth(p.x - du, p.y)) / (2 * du),
      (map.sample_depth(p.x, p.y + dv) - map.sample_depth(p.x, p.y - dv)) / (2 * dv));
  const double rate = 1 - glm::dot(gradient, glm::dvec2(ray.direction));
  return depth_error / std::max(0.05, std::abs(rate));
}

double steepest_slope(const ReliefMap& map) {
  return filtering_tolerance(map) * 256 * std::max(map.width, map.height);
}

std::vector<ProbeHit> probe(const std::string& technique, const ParamValues& params,
                            const ReliefMap& map, const std::vector<ProbeRay>& rays,
                            glm::dvec2 depth_aspect) {
  return test::probe(technique, params, map, rays, depth_aspect);
}

const std::vector<RenderCase>& render_cases() {
  static const std::vector<RenderCase> cases = [] {
    std::vector<RenderCase> c;
    auto planar = [](const std::string& kind, const std::map<std::string, double>& options) {
      return test::procedural_scene(kind, 64, 0.2, false, options);
    };
    const std::map<std::string, double> joints = {
        {"mortar_depth", 1.0}, {"rows", 4}, {"columns", 2}, {"mortar", 0.1}};
    c.push_back({"sines_45", planar("sines", {{"frequency", 2}}), View{45, 30}, true, true});
    SceneDesc grazing = planar("bricks", joints);
    grazing.size = 8;
    grazing.tile = 8;
    grazing.distance = 1.5;
    grazing.depth = 0.08;
    c.push_back({"bricks_joints_grazing_3", grazing, View{3, 30}, true, true});
    c.push_back({"bricks_joints_90", planar("bricks", joints), View{90, 0}, true, true});
    SceneDesc box = planar("domes", {});
    box.proxy = Proxy::Box;
    box.empty_floor = true;
    c.push_back({"domes_box_empty_floor_20", box, View{20, 60}, false, true});
    SceneDesc weave = test::weave_scene(64, TruthLevel::Layers);
    c.push_back({"weave_layers_35", weave, View{35, 30}, false});
    SceneDesc on_sphere = test::weave_scene(64, TruthLevel::Mesh);
    on_sphere.base.kind = "sphere";
    on_sphere.base.segments = 16;
    on_sphere.depth = 0.06;
    c.push_back({"weave_on_sphere_30", on_sphere, View{30, 30}, false});
    const std::string dir = std::filesystem::temp_directory_path() / "relieflab-contract";
    const std::string sphere =
        test::write_obj(test::uv_sphere({0, 0, 0}, 1, 32, 16), dir + "/sphere.obj");
    SceneDesc cells;
    cells.name = "cells";
    cells.relief.mesh_path = sphere;
    cells.relief.cells.active = true;
    cells.relief.cells.grid = 4;
    cells.relief.native = {32, 32};
    cells.proxy = Proxy::Box;
    cells.empty_floor = true;
    cells.truth = TruthLevel::Cells;
    cells.depth = cells.size;
    c.push_back({"sphere_cells_35", cells, View{35, 20}, false});
    SceneDesc cells_of_mesh = cells;
    cells_of_mesh.truth = TruthLevel::Mesh;
    c.push_back({"sphere_cells_mesh_truth_35", cells_of_mesh, View{35, 20}, false, false, true});
    SceneDesc object = cells;
    object.name = "object";
    object.relief.cells = {};
    object.relief.mesh_up = 1;
    object.relief.faces = 6;
    object.relief.native = {64, 64};
    object.truth = TruthLevel::Mesh;
    c.push_back({"sphere_faces_35", object, View{35, 20}, false});
    return c;
  }();
  return cases;
}

namespace {

struct CaseAssets {
  ReliefMap map;
  std::unique_ptr<GpuRelief> relief;
  std::unique_ptr<GpuBase> base;
  std::unique_ptr<ObjectPass> objects;
  Camera camera;
  GBuffer truth;
  glm::dvec2 span{0};
  std::vector<ProbeRay> pixel_rays;
  glm::dvec2 depth_aspect{0};
};

constexpr int kFrameSize = 48;

// Each pixel's tangent-space ray where it meets the planar base from above, and the longest
// lateral span (texels over the whole depth range) of any of them.
void planar_pixel_rays(const SceneDesc& scene, CaseAssets& a) {
  const PlanarBase base = planar_base(scene);
  a.depth_aspect =
      glm::dvec2(base.depth) / glm::dvec2(base.size / base.tile, base.size_v() / base.tile);
  for (int y = 0; y < a.camera.height; ++y)
    for (int x = 0; x < a.camera.width; ++x) {
      glm::dvec3 o, d;
      a.camera.pixel_ray(x, y, o, d);
      const glm::dvec3 s = base.texture_direction(d);
      if (!(s.z > 1e-9) || o.z <= 0) {
        a.pixel_rays.push_back({glm::vec3(0), glm::vec3(0, 0, 1)});
        continue;
      }
      const glm::dvec3 entry = base.texture_from_world(o + d * (-o.z / d.z));
      const glm::dvec3 step = s / s.z;
      a.pixel_rays.push_back({glm::vec3(entry), glm::vec3(step)});
      a.span = glm::max(a.span, glm::abs(glm::dvec2(step)) * glm::dvec2(a.map.width, a.map.height));
    }
}

CaseAssets& assets(size_t index) {
  static std::map<size_t, std::unique_ptr<CaseAssets>> built;
  auto& slot = built[index];
  if (slot) return *slot;
  GlContext::shared();
  const RenderCase& c = render_cases().at(index);
  // Built aside and kept only when whole: a build that throws fails its test, and must not
  // leave a half-built case for the next test to crash on.
  auto whole = std::make_unique<CaseAssets>();
  CaseAssets& a = *whole;
  const int res = c.scene.relief.native.longer();
  a.map = build_relief_asset(c.scene, res);
  a.relief = std::make_unique<GpuRelief>(a.map, c.scene.meta.runtime());
  a.base = std::make_unique<GpuBase>(make_base_geometry(c.scene));
  a.objects = std::make_unique<ObjectPass>(c.scene.objects);
  a.camera = make_camera(c.scene, c.view, kFrameSize, kFrameSize);
  const SceneTruth truth(c.scene, a.map, 2e-3);
  a.truth = truth.render(a.map, c.scene, a.camera, c.scene.effects);
  if (c.planar_rays) planar_pixel_rays(c.scene, a);
  slot = std::move(whole);
  return *slot;
}

Frame draw(size_t index, const std::string& technique, const ParamValues& params) {
  CaseAssets& a = assets(index);
  const RenderCase& c = render_cases()[index];
  Frame f;
  f.map = &a.map;
  f.truth = a.truth;
  f.pixel_rays = a.pixel_rays;
  f.depth_aspect = a.depth_aspect;
  auto t = TechniqueRegistry::instance().create(technique, params, "contract");
  t->prepare_scene(c.scene, a.map);
  FrameInput input{c.scene, a.map, *a.relief, *a.base, a.camera, c.scene.effects, a.objects.get()};
  RenderTarget target(kFrameSize, kFrameSize, RenderTarget::Kind::GBuffer);
  target.bind_and_clear();
  render_frame(*t, input, RenderTarget::Kind::GBuffer);
  target.read_back(f.image);
  target.read_back_costs(f.counts);
  const int res = c.scene.relief.native.longer();
  f.metrics = compare_gbuffers(f.image, f.truth, c.scene.depth, texel_world(c.scene, res),
                               c.scene.effects.has(Effect::AmbientOcclusion));
  f.columns = t->frame_columns();
  f.query = whole_frame_query(params, a.map);
  // A ray entering a box's side or a curved base is no longer than one across the map; a
  // planar base's pixels state their own.
  if (c.planar_rays) f.query.span_texels = a.span;
  return f;
}

}  // namespace

PixelOpCounts count_ops(size_t index, const std::string& technique, const ParamValues& params) {
  CaseAssets& a = assets(index);
  const RenderCase& c = render_cases()[index];
  auto t = TechniqueRegistry::instance().create(technique, params, "contract");
  t->prepare_scene(c.scene, a.map);
  FrameInput input{c.scene, a.map, *a.relief, *a.base, a.camera, c.scene.effects, a.objects.get()};
  OpCountBuffer ops(kFrameSize, kFrameSize);
  RenderTarget target(kFrameSize, kFrameSize, RenderTarget::Kind::ColorOnly);
  target.bind_and_clear();
  ops.bind();
  OpCountingScope counting;
  render_frame(*t, input, RenderTarget::Kind::ColorOnly);
  return ops.read_back();
}

std::pair<std::set<std::string>, std::set<std::string>> programs_of_two_frames(
    size_t index, const std::string& technique, const ParamValues& params) {
  CaseAssets& a = assets(index);
  const RenderCase& c = render_cases()[index];
  auto t = TechniqueRegistry::instance().create(technique, params, "contract");
  t->prepare_scene(c.scene, a.map);
  FrameInput input{c.scene, a.map, *a.relief, *a.base, a.camera, c.scene.effects, a.objects.get()};
  RenderTarget target(kFrameSize, kFrameSize, RenderTarget::Kind::GBuffer);
  auto frame = [&] {
    const ProgramUses uses;
    target.bind_and_clear();
    render_frame(*t, input, RenderTarget::Kind::GBuffer);
    std::set<std::string> digests;
    for (const auto& [key, desc] : uses.programs()) digests.insert(program_digest(desc));
    return digests;
  };
  std::set<std::string> first = frame();
  return {first, frame()};
}

// Several clauses read the same frame (its fetches, its finite outputs, its columns): each case,
// technique and setting is drawn once per process. llvmpipe draws the same bytes every time, so
// a second draw could only repeat the first.
Frame render(size_t index, const std::string& technique, const ParamValues& params) {
  static std::map<std::tuple<size_t, std::string, ParamValues>, Frame> drawn;
  const auto key = std::make_tuple(index, technique, params);
  if (const auto it = drawn.find(key); it != drawn.end()) return it->second;
  Frame f = draw(index, technique, params);
  drawn.emplace(key, f);
  return f;
}

std::vector<std::string> technique_names() {
  return TechniqueRegistry::instance().names();
}

const TechniqueInfo& info_of(const std::string& technique) {
  return TechniqueRegistry::instance().find(technique)->info;
}

ParamValues settings(const std::string& technique, const ParamValues& overrides) {
  return TechniqueRegistry::instance().resolve(technique, overrides, "contract");
}

std::optional<ParamValues> valid_settings(const std::string& technique,
                                          const ParamValues& overrides) {
  try {
    return settings(technique, overrides);
  } catch (const ConfigError&) {
    return std::nullopt;
  }
}

}  // namespace rl::contract
