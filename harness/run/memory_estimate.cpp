#include "run/memory_estimate.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "core/error.h"
#include "scene/relief_asset.h"

namespace rl {
namespace {

constexpr double kBytesPerPixel = 300;      // 2 G-buffers of 5 vec4 + targets + metrics
constexpr double kBytesPerTexel = 100;      // map, colour, GPU copies, mip and AO levels
constexpr double kBytesPerCellTexel = 20;   // distance, normal and colour per face texel
constexpr double kFacesPerSurfaceCell = 3;  // domain faces of a grey cell, at most
// A cell complex's mesh after subdivide, with its Embree truth: about 90 bytes a triangle as
// measured on the bunny at subdivide 0 to 2 (2026-12-06), rounded up.
constexpr double kBytesPerMeshTriangle = 120;
// A curved base's triangle with its share of the truth's prisms and sheet: 1.1 to 2.9 KB as
// measured on a sphere at 512 and 256 segments (2026-12-06), the larger taken.
constexpr double kBytesPerBaseTriangle = 3000;

// The triangles a generated curved base has at its `segments` (a sphere's or torus's chart is
// segments x segments / 2 quads; a cube's six faces segments / 8 quads a side); a mesh file's
// or the teapot's are its own, and small beside the maps.
double generated_base_triangles(const BaseDesc& base) {
  const double n = base.segments;
  if (base.kind == "sphere" || base.kind == "torus") return n * n;
  if (base.kind == "cube")
    return 12.0 * std::max(1.0, std::floor(n / 8)) * std::max(1.0, std::floor(n / 8));
  return 0;
}
// scene_shadows' map: its depth, and the op counts of its pass while they are counted.
constexpr double kBytesPerShadowTexel = 4 + 32;

std::string gib(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GiB", bytes / (1024.0 * 1024.0 * 1024.0));
  return text;
}

// A meta-relief's finer layers, each a map of its own size scaled as layer 0 is to `resolution`
// (with its AO map and GPU copy), and the bake of their combination where the scene bakes it.
double meta_relief_bytes(const SceneDesc& scene, int resolution) {
  double bytes = 0;
  for (const MetaLayerDesc& layer : scene.meta.layers) {
    const double side = meta_layer_resolution(scene, layer, resolution);
    const double native = std::max(1, layer.relief.native.longer());
    bytes += double(layer.relief.native.width) * layer.relief.native.height * (side / native) *
             (side / native) * kBytesPerTexel;
  }
  if (scene.meta.active() && !scene.meta.runtime()) {
    const MapSize base = scene.relief.native;
    const double side = scene.meta.bake_resolution > 0 ? scene.meta.bake_resolution
                                                       : std::max(base.width, base.height);
    bytes += side * side * kBytesPerTexel;
  }
  return bytes;
}

}  // namespace

MemoryEstimate estimate_cell_memory(const SweepConfig& config, const Cell& cell) {
  const SceneDesc& scene = config.scenes[cell.scene_index];
  const ReliefSourceDesc& r = scene.relief;
  const MapSize size = r.size_at(cell.texture_res);
  const double pixels = double(cell.width) * cell.height;
  const double texels = double(size.width) * size.height;
  // The footprint's truth: a G-buffer of samples^2 as many pixels (5 vec4 each) while traced.
  const double viewport =
      pixels * (kBytesPerPixel + 80.0 * config.footprint_samples * config.footprint_samples);
  // A colour map of its own size (color_resolution): its floats on the CPU and its texture; the
  // truth's (truth_color_resolution): its floats, and the truth's map they come with.
  const MapSize color = r.size_at(scene.color_texture_res);
  const MapSize truth_color = r.size_at(scene.truth_color_texture_res);
  const double color_maps =
      (scene.color_texture_res > 0 ? double(color.width) * color.height * 2 * 16 : 0) +
      (scene.truth_color_texture_res > 0
           ? double(truth_color.width) * truth_color.height * 16 + texels * kBytesPerTexel
           : 0);
  const double maps = texels * kBytesPerTexel * std::max(1, r.faces) + color_maps +
                      meta_relief_bytes(scene, cell.texture_res);
  double cells = 0;
  if (r.cells.active) {
    const double n = r.cells.grid > 0 ? r.cells.grid : r.cells.grid_max;
    cells = 6 * n * n * kFacesPerSurfaceCell * texels * kBytesPerCellTexel;  // texels per face
    // subdivide = k splits every triangle into 4^k.
    cells += double(r.mesh_triangles) * std::pow(4.0, r.cells.subdivide) * kBytesPerMeshTriangle;
  }
  const double shadow_map =
      scene.effects.has(Effect::SceneShadows)
          ? double(scene.shadow_map.size) * scene.shadow_map.size * kBytesPerShadowTexel
          : 0;
  const double base = generated_base_triangles(scene.base) * kBytesPerBaseTriangle;
  MemoryEstimate e;
  e.bytes = viewport + maps + cells + shadow_map + base;
  if (base >= viewport && base >= maps && base >= cells && base >= shadow_map)
    e.what = "its curved base and its truth (" + gib(base) + ")";
  else if (shadow_map >= viewport && shadow_map >= maps && shadow_map >= cells)
    e.what = "its shadow map (" + gib(shadow_map) + ")";
  else if (cells >= viewport && cells >= maps)
    e.what = "its cell complex's maps (" + gib(cells) + ")";
  else if (maps >= viewport)
    e.what = "its relief maps (" + gib(maps) + ")";
  else
    e.what = "its G-buffers (" + gib(viewport) + ")";
  return e;
}

double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? double(pages) * double(page) : 0.0;
}

namespace {

// A cgroup's memory limit in bytes, from its control file's text ("max", or a number): 0 when
// none.
double cgroup_limit(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return end != text.c_str() && v > 0 && v < 1e18 ? v : 0;
}

// The first line of a small file ("" when it cannot be read).
std::string first_line(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

// The memory limit of this process's cgroup (v2 memory.max, v1 memory.limit_in_bytes), as
// Slurm's --mem and containers set it: 0 when none.
double cgroup_memory_limit() {
  std::ifstream in("/proc/self/cgroup");
  for (std::string line; std::getline(in, line);) {
    const size_t colon = line.rfind(':');
    if (colon == std::string::npos) continue;
    const std::string path = line.substr(colon + 1);
    const bool v2 = line.rfind("0::", 0) == 0;
    const bool v1 = line.find(":memory:") != std::string::npos;
    if (!v2 && !v1) continue;
    const std::string file = v2 ? "/sys/fs/cgroup" + path + "/memory.max"
                                : "/sys/fs/cgroup/memory" + path + "/memory.limit_in_bytes";
    if (const double limit = cgroup_limit(first_line(file)); limit > 0) return limit;
  }
  return 0;
}

}  // namespace

MemoryLimit usable_memory() {
  MemoryLimit m{physical_memory_bytes(), "this machine has"};
  rlimit as{};
  if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY &&
      (m.bytes <= 0 || double(as.rlim_cur) < m.bytes))
    m = {double(as.rlim_cur), "this process may use (its address-space limit, ulimit -v)"};
  if (const double cg = cgroup_memory_limit(); cg > 0 && (m.bytes <= 0 || cg < m.bytes))
    m = {cg, "this process's cgroup may use (memory.max, as Slurm's --mem sets it)"};
  return m;
}

void refuse_cells_beyond_memory(const SweepConfig& config, const std::vector<Cell>& cells) {
  const MemoryLimit limit = usable_memory();
  const double have = limit.bytes;
  if (have <= 0) return;
  for (const Cell& c : cells) {
    const MemoryEstimate e = estimate_cell_memory(config, c);
    if (e.bytes <= have) continue;
    const SceneDesc& scene = config.scenes[c.scene_index];
    throw ConfigError(
        config.source + ": scene '" + scene.name + "' at viewport " + std::to_string(c.width) +
        "x" + std::to_string(c.height) + ", texture_res " + std::to_string(c.texture_res) +
        " needs about " + gib(e.bytes) + ", mostly " + e.what + ", and " + limit.what + " " +
        gib(have) +
        ": lower the viewport, texture_res, a cell complex's grid or subdivide, or a curved "
        "base's segments (nothing was run)");
  }
}

}  // namespace rl
