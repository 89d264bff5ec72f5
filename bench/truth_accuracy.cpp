// How far the heightfield truth is from the exact bilinear surface, in the headline's units
// (texels at the view), per map size and elevation; and what the truth costs. Every pixel of a
// truth G-buffer (base proxy, the view filling the viewport) is compared with the exact walk of
// relief/heightfield_reference.h (per texel cell, the ray's depth minus the bilinear depth is a
// quadratic solved in double) on the same texture-space ray. Not part of CI: the closing notes'
// before/after tables of the exact-truth goal (2026-12-03) come from it.
//
//   truth_accuracy [--maps panel,pits,rockwall,bricks] [--sizes 512,1024,2048]
//                  [--elevations 1,5,20,45,90] [--viewport 512]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "bench_support.h"
#include "core/parallel.h"
#include "relief/heightfield_reference.h"
#include "scene/base_mesh.h"
#include "scene/relief_asset.h"
#include "truth/heightfield_truth.h"
#include "truth/truth_render.h"

namespace rl {
namespace {

SceneDesc study_scene(const std::string& name) {
  SceneDesc scene;
  scene.name = name;
  const std::string assets = std::string(RELIEFLAB_SOURCE_DIR) + "/assets/relief/";
  if (name == "panel" || name == "pits") {
    scene.relief.normal_path = assets + "trak5/" + name + "1_n.png";
    scene.relief.normalize = true;
    scene.relief.native = {512, 512};
  } else if (name == "rockwall") {
    scene.relief.depth_path = assets + "rockwall/rockwall_height.bmp";
    scene.relief.native = {256, 256};
  } else {
    scene.relief.procedural = name;
    scene.relief.native = {512, 512};
  }
  return scene;
}

struct Study {
  long covered = 0, hit_miss = 0, over_001 = 0, over_05 = 0, over_1 = 0;
  double p99 = 0, max = 0, truth_ms = 0, build_ms = 0, bound_depth = 0;
  int subdivision = 0;
};

Study study(const SceneDesc& scene, const ReliefMap& map, const HeightfieldTruth& truth,
            double elevation, int viewport) {
  Study s;
  s.subdivision = truth.subdivision();
  s.bound_depth = truth.tessellation_bound();
  s.build_ms = truth.build_ms();
  const Camera camera = make_camera(scene, View{elevation, 30}, viewport, viewport);
  TruthStats stats;
  const GBuffer g = render_truth(truth, map, scene, camera, EffectSet{}, &stats);
  s.truth_ms = stats.trace_ms;
  const PlanarBase base = planar_base(scene);
  const double texel = base.texel_world(map.width);
  std::vector<double> err(g.size(), -1);
  std::vector<char> disagree(g.size(), 0);
  parallel_for(g.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      glm::dvec3 eye, dir;
      camera.pixel_ray(int(i % camera.width), int(i / camera.width), eye, dir);
      const glm::dvec3 o = base.texture_from_world(eye), d = base.texture_direction(dir);
      bool exact_hit = false;
      glm::dvec3 exact_world(0);
      if (d.z > 0) {
        const double t_top = -o.z / d.z;
        const glm::dvec3 entry = o + d * t_top;
        if (t_top > 0 && entry.x >= 0 && entry.y >= 0 && entry.x <= scene.tile &&
            entry.y <= scene.tile) {
          const ReferenceHit r = intersect_heightfield(map, entry, d, (1.0 + 1e-4) / d.z);
          exact_hit = true;  // a ray through the base always meets the floor at depth <= 1
          exact_world = eye + dir * (t_top + (r.hit ? r.t : (1.0 - entry.z) / d.z));
        }
      }
      if (exact_hit != g.covered(i)) {
        disagree[i] = 1;
        continue;
      }
      if (exact_hit)
        err[i] = glm::length(glm::dvec3(glm::vec3(g.position[i])) - exact_world) / texel;
    }
  });
  std::vector<double> values;
  for (size_t i = 0; i < g.size(); ++i) {
    s.hit_miss += disagree[i];
    if (err[i] < 0) continue;
    values.push_back(err[i]);
    s.over_001 += err[i] > 0.01;
    s.over_05 += err[i] > 0.5;
    s.over_1 += err[i] > 1.0;
  }
  s.covered = long(values.size());
  if (!values.empty()) {
    std::sort(values.begin(), values.end());
    s.p99 = values[std::min(values.size() - 1, size_t(0.99 * double(values.size())))];
    s.max = values.back();
  }
  return s;
}

}  // namespace
}  // namespace rl

int main(int argc, char** argv) {
  using namespace rl;
  std::vector<std::string> maps = {"panel", "pits", "rockwall", "bricks"};
  std::vector<std::string> sizes = {"512", "1024", "2048"};
  std::vector<std::string> elevations = {"1", "5", "20", "45", "90"};
  int viewport = 512;
  for (int a = 1; a + 1 < argc; a += 2) {
    const std::string flag = argv[a], value = argv[a + 1];
    if (flag == "--maps")
      maps = bench::split(value);
    else if (flag == "--sizes")
      sizes = bench::split(value);
    else if (flag == "--elevations")
      elevations = bench::split(value);
    else if (flag == "--viewport")
      viewport = std::stoi(value);
    else {
      std::fprintf(stderr, "truth_accuracy: unknown option %s\n", flag.c_str());
      return 2;
    }
  }
  std::printf(
      "| map | size | elevation | k | bound (depth) | build ms | trace ms | covered px | "
      "hit/miss differ | > 0.01 texel | > 0.5 texel | > 1 texel | p99 texels | max texels |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& name : maps) {
    const SceneDesc scene = study_scene(name);
    for (const std::string& size : sizes) {
      const ReliefMap map = build_relief_asset(scene, std::stoi(size));
      const HeightfieldTruth truth(map, 2e-3);
      for (const std::string& el : elevations) {
        SceneDesc framed =
            scene;  // the quad lengthened (more tiles) so the view fills the viewport
        apply_fill_framing(framed, std::stod(el), 1.0);
        const Study s = study(framed, map, truth, std::stod(el), viewport);
        const double n = std::max<double>(1, double(s.covered));
        std::printf(
            "| %s | %dx%d | %s | %d | %.2g | %.0f | %.0f | %ld | %ld | %.3f%% | %.3f%% | "
            "%.3f%% | %.3g | %.3g |\n",
            name.c_str(), map.width, map.height, el.c_str(), s.subdivision, s.bound_depth,
            s.build_ms, s.truth_ms, s.covered, s.hit_miss, 100.0 * s.over_001 / n,
            100.0 * s.over_05 / n, 100.0 * s.over_1 / n, s.p99, s.max);
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
