#include "run/memory_estimate.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "core/error.h"

namespace rl {
namespace {

constexpr double kBytesPerPixel = 300;      // 2 G-buffers of 5 vec4 + targets + metrics
constexpr double kBytesPerTexel = 100;      // map, colour, GPU copies, mip and AO levels
constexpr double kBytesPerCellTexel = 20;   // distance, normal and colour per face texel
constexpr double kFacesPerSurfaceCell = 3;  // domain faces of a grey cell, at most
// scene_shadows' map: its depth, and the op counts of its pass while they are counted.
constexpr double kBytesPerShadowTexel = 4 + 32;

std::string gib(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GiB", bytes / (1024.0 * 1024.0 * 1024.0));
  return text;
}

// A meta-relief's finer layers, each a map of its own size (with its AO map and GPU copy),
// and the bake of their combination where the scene bakes it.
double meta_relief_bytes(const SceneDesc& scene) {
  double bytes = 0;
  for (const MetaLayerDesc& layer : scene.meta.layers)
    bytes += double(layer.relief.native.width) * layer.relief.native.height * kBytesPerTexel;
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
  const double maps =
      texels * kBytesPerTexel * std::max(1, r.faces) + color_maps + meta_relief_bytes(scene);
  double cells = 0;
  if (r.cells.active) {
    const double n = r.cells.grid > 0 ? r.cells.grid : r.cells.grid_max;
    cells = 6 * n * n * kFacesPerSurfaceCell * texels * kBytesPerCellTexel;  // texels per face
  }
  const double shadow_map =
      scene.effects.has(Effect::SceneShadows)
          ? double(scene.shadow_map.size) * scene.shadow_map.size * kBytesPerShadowTexel
          : 0;
  MemoryEstimate e;
  e.bytes = viewport + maps + cells + shadow_map;
  if (shadow_map >= viewport && shadow_map >= maps && shadow_map >= cells)
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

void refuse_cells_beyond_memory(const SweepConfig& config, const std::vector<Cell>& cells) {
  const double have = physical_memory_bytes();
  if (have <= 0) return;
  for (const Cell& c : cells) {
    const MemoryEstimate e = estimate_cell_memory(config, c);
    if (e.bytes <= have) continue;
    const SceneDesc& scene = config.scenes[c.scene_index];
    throw ConfigError(config.source + ": scene '" + scene.name + "' at viewport " +
                      std::to_string(c.width) + "x" + std::to_string(c.height) + ", texture_res " +
                      std::to_string(c.texture_res) + " needs about " + gib(e.bytes) + ", mostly " +
                      e.what + ", and this machine has " + gib(have) +
                      ": lower the viewport, texture_res or grid (nothing was run)");
  }
}

}  // namespace rl
