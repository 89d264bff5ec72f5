// Apaza & Andujar, Section 4: "the ray throughput we achieve also holds for reflected and
// refracted rays". The cell-complex ray caster (its probe pass: one ray per fragment) run on
// three sets of rays through a viewport's pixels, each pixel's ray in that pixel so that a GPU's
// 8 x 4 lockstep groups hold neighbouring pixels, as a screen pass would:
//
//   primary    the camera's rays that meet the object's cube;
//   primary_near  those of the refracted set's camera, aimed at the object without the glass and
//              zoomed on it: primary rays that meet the object as often as the refracted ones;
//   reflected  the camera's rays reflected by a mirror sphere beside the cube, where they meet it;
//   refracted  the camera's rays through a glass sphere (index 1.5) in front of the cube,
//              refracted in and out, where they meet it;
//   none       no ray at all (every pixel inactive): the pass's own overhead.
//
// Per set: the rays that meet the cube, the probe pass's llvmpipe time (fastest of --runs, upload
// and read-back included, the same for every set), its op counts priced by the NVIDIA H200 cost
// model (results/gpu-model/) and the hits against the encoded surface's CPU truth. Rows to stdout
// (scripts/secondary-rays-rows.sh makes results/apaza-secondary-rays/rows.csv of them).
//
//   secondary_rays [--meshes bunny,teapot,dragon] [--viewport 512] [--runs 7]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "bench_support.h"
#include "config/config.h"
#include "core/cost_model.h"
#include "core/ray_box.h"
#include "gl/context.h"
#include "gl/op_count_buffer.h"
#include "gpu/gpu_scene.h"
#include "metrics/op_cost.h"
#include "scene/relief_asset.h"
#include "technique/technique.h"
#include "truth/cell_complex_truth.h"

namespace rl {
namespace {

const glm::dvec3 kCentre(0.5);  // of the object's cube [0, 1]^3, where every ray lives

glm::dvec3 direction_at(double elevation_deg, double azimuth_deg) {
  const double el = glm::radians(elevation_deg), az = glm::radians(azimuth_deg);
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

// A pinhole camera at `eye` aimed at `target`, `viewport` pixels square.
Camera camera_at(const glm::dvec3& eye, const glm::dvec3& target, double fov_deg, int viewport) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.up = {0, 0, 1};
  c.fov_y_deg = fov_deg;
  c.width = c.height = viewport;
  return c;
}

// The first t > 1e-9 where o + t d meets the sphere, or -1.
double hit_sphere(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& c, double r) {
  const glm::dvec3 oc = o - c;
  const double b = glm::dot(oc, d), disc = b * b - (glm::dot(oc, oc) - r * r);
  if (disc < 0) return -1;
  const double s = std::sqrt(disc);
  if (-b - s > 1e-9) return -b - s;
  return -b + s > 1e-9 ? -b + s : -1;
}

struct Sphere {
  glm::dvec3 centre;
  double radius;
};

// A camera ray's way on to the cube: unchanged, reflected off a mirror, or refracted through a
// glass ball. False where it leaves the scene (misses the sphere, or total internal reflection).
using Bounce = bool (*)(const Sphere&, glm::dvec3&, glm::dvec3&);

bool straight(const Sphere&, glm::dvec3&, glm::dvec3&) {
  return true;
}

bool reflect_off(const Sphere& s, glm::dvec3& o, glm::dvec3& d) {
  const double t = hit_sphere(o, d, s.centre, s.radius);
  if (t < 0) return false;
  o += d * t;
  d = glm::reflect(d, glm::normalize(o - s.centre));
  return true;
}

bool refract_through(const Sphere& s, glm::dvec3& o, glm::dvec3& d) {
  constexpr double kGlass = 1.5;
  const double t_in = hit_sphere(o, d, s.centre, s.radius);
  if (t_in < 0) return false;
  o += d * t_in;
  d = glm::refract(d, glm::normalize(o - s.centre), 1.0 / kGlass);
  const double t_out = hit_sphere(o + d * 1e-9, d, s.centre, s.radius);
  if (t_out < 0) return false;
  o += d * t_out;
  d = glm::refract(d, -glm::normalize(o - s.centre), kGlass);
  return glm::dot(d, d) > 0.5;  // zero on total internal reflection
}

// The probe pass lays its rays out in rows of kProbeRow (run_probe_pass): each of the view's rows
// is padded to one, so that the pass's pixel (x, y) is the view's.
constexpr int kProbeRow = 1024;

// One probe ray per pixel: where the pixel's (bounced) ray enters the cube, pointing on; a
// zero direction where it does not meet it, and in the padding (the search ends at once).
std::vector<ProbeRay> pixel_rays(const Camera& cam, const Sphere& sphere, Bounce bounce,
                                 long& active) {
  std::vector<ProbeRay> rays(size_t(kProbeRow) * cam.height,
                             ProbeRay{glm::vec3(0), glm::vec3(0), glm::vec2(0)});
  active = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      glm::dvec3 o, d;
      cam.pixel_ray(x, y, o, d);
      double t_in = 0, t_out = 0;
      if (!bounce(sphere, o, d) ||
          !clip_ray_to_box(o, d, glm::dvec3(0), glm::dvec3(1), t_in, t_out))
        continue;
      rays[size_t(y) * kProbeRow + x] = {glm::vec3(o + d * t_in), glm::vec3(d), glm::vec2(0)};
      ++active;
    }
  return rays;
}

struct RaySet {
  const char* name;
  Camera camera;
  Sphere sphere;
  Bounce bounce;
};

// The sets' scenes, in the cube's space: a camera on the cube; one on a mirror ball at the
// cube's side, seeing the cube in it; one looking at the cube through a glass ball.
std::vector<RaySet> ray_sets(int viewport) {
  const glm::dvec3 mirror = kCentre + glm::dvec3(1.6, 0, 0);
  const glm::dvec3 along = direction_at(20, 60);
  const glm::dvec3 glass = kCentre + 1.6 * along;
  return {{"none",
           camera_at(kCentre + 2.4 * direction_at(30, 30), kCentre, 40, viewport),
           {kCentre, 0},
           [](const Sphere&, glm::dvec3&, glm::dvec3&) { return false; }},
          {"primary",
           camera_at(kCentre + 2.4 * direction_at(30, 30), kCentre, 40, viewport),
           {kCentre, 0},
           straight},
          {"reflected",
           camera_at(mirror + glm::dvec3(-1.05, -0.2, 0.2), mirror, 50, viewport),
           {mirror, 0.75},
           reflect_off},
          {"primary_near",
           camera_at(kCentre + 3.2 * along, kCentre, 12, viewport),
           {kCentre, 0},
           straight},
          {"refracted",
           camera_at(kCentre + 3.2 * along, glass, 24, viewport),
           {glass, 0.5},
           refract_through}};
}

struct Measured {
  long active = 0, hits = 0, disagree = 0;
  double probe_ms = 0, fetches = 0, model_ms = 0, warp_fetch_ops = 0;
};

// The probe pass's time: the fastest of `runs` after two warm-ups (the first passes of a
// process pay for compiling and first touches; the fastest is the least disturbed).
double fastest_probe_ms(Technique& t, const ReliefMap& map, const GpuRelief& relief,
                        const std::vector<ProbeRay>& rays, int runs) {
  for (int i = 0; i < 2; ++i) (void)t.probe(map, relief, rays, glm::dvec2(1));
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    (void)t.probe(map, relief, rays, glm::dvec2(1));
    glFinish();
    ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return *std::min_element(ms.begin(), ms.end());
}

Measured measure(Technique& t, const ReliefMap& map, const GpuRelief& relief, const RaySet& set,
                 const CostModel& model, int runs) {
  Measured m;
  const std::vector<ProbeRay> rays = pixel_rays(set.camera, set.sphere, set.bounce, m.active);
  const int w = kProbeRow, h = set.camera.height;
  m.probe_ms = fastest_probe_ms(t, map, relief, rays, runs);
  {
    OpCountBuffer ops(w, h);
    ops.bind();
    OpCountingScope counting(1);
    (void)t.probe(map, relief, rays, glm::dvec2(1));
    PixelOpCounts counts = ops.read_back();
    counts.group_stride = 1;
    const OpCost cost = op_cost(counts);
    m.model_ms = predict_frame_ms(model, {double(w) * h, double(w) * h, cost.warp_ops_per_px});
    m.warp_fetch_ops = cost.warp_ops_per_px[int(OpKind::Fetch)] * w * h;
  }
  const std::vector<ProbeHit> gpu = t.probe(map, relief, rays, glm::dvec2(1));
  const CellComplexTruth truth(map.cells);
  const double texel = 1.0 / (map.cells->grid() * map.cells->resolution());
  for (size_t i = 0; i < rays.size(); ++i) {
    if (rays[i].direction == glm::vec3(0)) continue;
    const TruthHit cpu =
        truth.intersect(glm::dvec3(rays[i].origin), glm::dvec3(rays[i].direction), 0, 2);
    m.hits += gpu[i].hit;
    m.fetches += gpu[i].fetches;
    m.disagree += gpu[i].hit != cpu.hit || (cpu.hit && std::abs(gpu[i].t - cpu.t) > 2 * texel);
  }
  return m;
}

// One row per set: its time, op cost and price over the empty pass's (the "none" set, first),
// per ray that meets the cube.
void print_row(const std::string& mesh, int grid, const char* set, int viewport, const Measured& m,
               const Measured& empty) {
  const double active = std::max<double>(m.active, 1);
  const double over_ms = m.probe_ms - empty.probe_ms;
  std::printf("%s,%d,%s,%d,%ld,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g\n", mesh.c_str(), grid,
              set, viewport, m.active, 100.0 * m.hits / active, m.probe_ms, over_ms,
              m.active ? m.active / over_ms / 1e3 : 0.0, m.fetches / active,
              (m.warp_fetch_ops - empty.warp_fetch_ops) / active, m.model_ms,
              1e6 * (m.model_ms - empty.model_ms) / active, 100.0 * m.disagree / active);
  std::fflush(stdout);
}

void run(const std::vector<std::string>& meshes, int viewport, int runs) {
  GlContext::shared();
  std::printf(
      "mesh,grid,rays,viewport,active_rays,hit_pct,probe_ms,over_empty_ms,mrays_per_s,"
      "fetches_mean,warp_fetch_ops_per_ray,model_frame_ms,model_ns_per_ray,disagree_pct\n");
  for (const std::string& mesh : meshes) {
    const SweepConfig config = bench::table1_mesh_config(mesh, "secondary_rays");
    const SceneDesc& scene = config.scenes.front();
    const ReliefMap map = build_relief_asset(scene, 64);
    GpuRelief relief(map);
    auto t = TechniqueRegistry::instance().create("cell_complex", {}, "secondary_rays");
    t->prepare_scene(scene, map);
    Measured empty;
    for (const RaySet& set : ray_sets(viewport)) {
      const Measured m = measure(*t, map, relief, set, *config.cost_model, runs);
      if (std::string(set.name) == "none") empty = m;
      print_row(mesh, map.cells->grid(), set.name, viewport, m, empty);
    }
  }
}

}  // namespace
}  // namespace rl

int main(int argc, char** argv) {
  std::vector<std::string> meshes = {"bunny", "teapot", "dragon"};
  int viewport = 512, runs = 7;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--meshes"))
      meshes = rl::bench::split(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--viewport"))
      viewport = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--runs"))
      runs = std::atoi(argv[i + 1]);
    else {
      std::fprintf(stderr, "secondary_rays: unknown option %s\n", argv[i]);
      return 2;
    }
  }
  if (viewport < 8 || viewport > 1024 || runs < 1) {
    std::fprintf(stderr, "secondary_rays: --viewport 8 to 1024, --runs at least 1\n");
    return 2;
  }
  try {
    rl::run(meshes, viewport, runs);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "secondary_rays: %s\n", e.what());
    return 1;
  }
  return 0;
}
