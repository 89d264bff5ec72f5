#include "support/test_support.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <glm/gtc/constants.hpp>

#include "core/atomic_write.h"
#include "core/precompute_cache.h"
#include "gl/context.h"
#include "gl/render_target.h"
#include "gpu/gpu_scene.h"
#include "output/result_store.h"
#include "run/cells.h"
#include "run/runner.h"
#include "scene/base_mesh.h"
#include "scene/relief_asset.h"
#include "truth/make_truth.h"

namespace rl::test {

SceneDesc procedural_scene(const std::string& kind, int resolution, double depth, bool quantize,
                           const std::map<std::string, double>& options) {
  SceneDesc s;
  s.name = kind;
  s.relief.procedural = kind;
  s.relief.options = options;
  s.relief.native = {resolution, resolution};
  s.depth = depth;
  s.quantize = quantize;
  return s;
}

SceneDesc weave_scene(int resolution, TruthLevel truth) {
  SceneDesc s;
  s.name = "weave";
  s.relief.procedural = "weave";
  s.relief.layers = 4;
  s.relief.native = {resolution, resolution};
  s.truth = truth;
  s.empty_floor = true;
  s.tile = 2;
  s.depth = 0.15;
  return s;
}

Measured measure(const SceneDesc& scene, const std::string& technique, const ParamValues& params,
                 const View& view, int size, double truth_tolerance) {
  GlContext::shared();
  const int res = scene.relief.native.longer();
  ReliefMap map = build_relief_asset(scene, res);
  attach_ao_map(map, scene, texel_world(scene, res));
  GpuRelief relief(map, scene.meta.runtime());
  GpuBase base(make_base_geometry(scene));
  ObjectPass objects(scene.objects);
  const SceneTruth truth(scene, map, truth_tolerance);
  const Camera camera = make_camera(scene, view, size, size);
  Measured m;
  m.truth = truth.render(map, scene, camera, scene.effects, &m.truth_stats);
  auto t = TechniqueRegistry::instance().create(technique, params, "test");
  t->prepare_scene(scene, map);
  std::unique_ptr<ShadowMapPass> shadow_map;
  if (scene.effects.has(Effect::SceneShadows)) shadow_map = std::make_unique<ShadowMapPass>(scene);
  FrameInput frame{scene, map, relief, base, camera, scene.effects, &objects, shadow_map.get()};
  RenderTarget target(size, size, RenderTarget::Kind::GBuffer);
  target.bind_and_clear();
  render_frame(*t, frame, RenderTarget::Kind::GBuffer);
  target.read_back(m.technique);
  target.read_back_costs(m.counts);
  m.metrics = compare_gbuffers(m.technique, m.truth, scene.depth, texel_world(scene, res),
                               scene.effects.has(Effect::AmbientOcclusion),
                               scene.effects.has(Effect::SceneShadows));
  return m;
}

std::string write_obj(const TriangleMesh& mesh, const std::string& path) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ostringstream f;
  for (const glm::vec3& p : mesh.positions) f << "v " << p.x << " " << p.y << " " << p.z << "\n";
  for (const glm::uvec3& t : mesh.triangles)
    f << "f " << t.x + 1 << " " << t.y + 1 << " " << t.z + 1 << "\n";
  // Replaced whole, never rewritten in place: the contract's test processes run at once and
  // share this file (one read it half-written: "OBJ-file is too small", then a crash).
  write_text_atomic(path, f.str());
  return path;
}

std::vector<TangentRay> random_tangent_rays(int n, double min_el, double max_el, double aspect,
                                            unsigned seed, double start_depth) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 2), el(min_el, max_el), az(0, 360);
  std::vector<TangentRay> rays;
  for (int i = 0; i < n; ++i) {
    const double e = glm::radians(el(rng)), a = glm::radians(az(rng));
    const double lateral = aspect / std::tan(e);
    const double x = u(rng), y = u(rng);
    rays.push_back({{x, y, start_depth}, {lateral * std::cos(a), lateral * std::sin(a), 1.0}});
  }
  return rays;
}

std::vector<ProbeRay> as_probe_rays(const std::vector<TangentRay>& rays) {
  std::vector<ProbeRay> out;
  for (const TangentRay& r : rays) out.push_back({glm::vec3(r.origin), glm::vec3(r.direction)});
  return out;
}

SceneDesc curved_scene(const std::string& base, const std::string& relief, int res, double depth) {
  SceneDesc s = procedural_scene(relief, res, depth);
  s.name = base + "_" + relief;
  s.base.kind = base;
  s.base.segments = 32;
  return s;
}

ReliefMap random_map(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<float> d;
  for (int i = 0; i < n * n; ++i) d.push_back(u(rng));
  return map_from_depths(n, n, d);
}

std::vector<ProbeHit> probe(const std::string& technique, const ParamValues& params,
                            const ReliefMap& map, const GpuRelief& relief,
                            const std::vector<ProbeRay>& rays, glm::dvec2 depth_aspect) {
  auto t = TechniqueRegistry::instance().create(technique, params, "test");
  t->prepare(map);
  return t->probe(map, relief, rays, depth_aspect);
}

std::vector<ProbeHit> probe(const std::string& technique, const ParamValues& params,
                            const ReliefMap& map, const std::vector<ProbeRay>& rays,
                            glm::dvec2 depth_aspect) {
  GlContext::shared();
  return probe(technique, params, map, GpuRelief(map), rays, depth_aspect);
}

ReliefMap map_from_depths(int w, int h, const std::vector<float>& depths) {
  ReliefMap m;
  m.width = w;
  m.height = h;
  m.relief.reserve(depths.size());  // 2048^2 maps: growing by doubling was copies and page faults
  m.color.reserve(depths.size());
  for (float v : depths) {
    m.relief.push_back(glm::vec4(0.5f, 0.5f, 1.0f, v));
    m.color.push_back(glm::vec4(1));
  }
  return m;
}

TriangleMesh uv_sphere(glm::dvec3 c, double r, int slices, int stacks) {
  TriangleMesh m;
  for (int s = 0; s <= stacks; ++s)
    for (int i = 0; i <= slices; ++i) {
      const double th = M_PI * s / stacks, ph = 2 * M_PI * i / slices;
      m.positions.push_back(
          glm::vec3(c + r * glm::dvec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph),
                                       std::cos(th))));
    }
  auto at = [&](int s, int i) { return unsigned(s * (slices + 1) + i); };
  for (int s = 0; s < stacks; ++s)
    for (int i = 0; i < slices; ++i) {
      if (s > 0) m.triangles.push_back({at(s, i), at(s + 1, i), at(s, i + 1)});
      if (s < stacks - 1) m.triangles.push_back({at(s, i + 1), at(s + 1, i), at(s + 1, i + 1)});
    }
  m.lo = c - r;
  m.hi = c + r;
  return m;
}

TriangleMesh layer_boxes(const std::vector<std::tuple<double, double, double, double>>& spans,
                         bool flip) {
  TriangleMesh m;
  for (const auto& [lo, hi, top, bottom] : spans) {
    const uint32_t b = uint32_t(m.positions.size());
    for (int k = 0; k < 8; ++k)
      m.positions.emplace_back(k & 1 ? hi : lo, k & 2 ? hi : lo, k & 4 ? -top : -bottom);
    // Faces as quads (a, b, c, d) counter-clockwise seen from outside.
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
      glm::uvec3 t0(b + q[0], b + q[1], b + q[2]), t1(b + q[0], b + q[2], b + q[3]);
      if (flip) std::swap(t0.y, t0.z), std::swap(t1.y, t1.z);
      m.triangles.push_back(t0);
      m.triangles.push_back(t1);
    }
  }
  m.lo = glm::dvec3(0, 0, -1);
  m.hi = glm::dvec3(1, 1, 0);
  return m;
}

TriangleMesh hollow_ball() {
  TriangleMesh shell = uv_sphere({0.5, 0.5, 0.5}, 0.4, 64, 32);
  const TriangleMesh inner = uv_sphere({0.5, 0.5, 0.5}, 0.2, 64, 32);
  const unsigned offset = unsigned(shell.positions.size());
  shell.positions.insert(shell.positions.end(), inner.positions.begin(), inner.positions.end());
  for (glm::uvec3 t : inner.triangles)
    shell.triangles.push_back({t.x + offset, t.z + offset, t.y + offset});
  return shell;
}

std::string scratch_dir(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "relieflab-tests" /
      (std::string(info->test_suite_name()) + "." + info->name() + "." + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir.parent_path());
  return dir.string();
}

bool read_precompute_cache_elsewhere(const std::string& folder, const std::string& options,
                                     uint64_t map_hash, void* out, size_t bytes) {
  return read_precompute_cache(folder, options, map_hash, out, bytes);
}

SweepConfig run_sweep_in(const std::string& toml, const std::string& dir) {
  const SweepConfig config = parse_sweep_config(toml, dir + "/sweep.toml", dir);
  RunOptions opt;
  opt.out_dir = dir + "/out";
  opt.progress = false;
  run_sweep(config, opt);
  return config;
}

std::map<std::string, nlohmann::json> rows_by_scene(const SweepConfig& config,
                                                    const std::string& dir) {
  ResultStore store(dir + "/out/results.sqlite");
  std::map<std::string, nlohmann::json> rows;
  for (const Cell& c : expand_cells(config)) {
    const std::string& scene = config.scenes[c.scene_index].name;
    const auto row = store.row(c.key);
    if (!row) throw std::runtime_error("no stored row for cell " + c.key + " of " + scene);
    if (!rows.emplace(scene, *row).second)
      throw std::runtime_error("scene " + scene + " has more than one cell");
  }
  return rows;
}

int run_cli(const std::string& args, std::string& output, const std::string& prefix) {
  const std::string cmd = prefix + RELIEFLAB_CLI + " " + args + " 2>&1";
  output.clear();
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buf;
  while (fgets(buf.data(), buf.size(), pipe)) output += buf.data();
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string write_small_sweep(const std::string& dir, const std::string& sweep_extra) {
  std::filesystem::create_directories(dir);
  const std::string config = dir + "/sweep.toml";
  std::ofstream(config) << "[sweep]\nname = \"small\"\nelevations = [45, 20]\nviewports = [32]\n"
                           "frames = 1\nwarmup = 0\n"
                        << sweep_extra
                        << "[[scene]]\nname = \"bricks\"\n"
                           "relief = { procedural = \"bricks\", resolution = 32 }\n"
                           "[[technique]]\nname = \"relief\"\nlinear_steps = [8, 16]\n";
  return config;
}

void store_exec(const std::string& db_path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(db_path.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error), SQLITE_OK) << error;
  sqlite3_free(error);
  sqlite3_close(db);
}

}  // namespace rl::test
