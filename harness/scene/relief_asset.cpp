#include "scene/relief_asset.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/elapsed.h"
#include "core/hash.h"
#include "core/precompute_cache.h"
#include "relief/cell_complex.h"
#include "relief/heightfield_faces.h"
#include "relief/image_io.h"
#include "relief/layer_bake.h"
#include "relief/mesh_bake.h"
#include "relief/meta_relief.h"
#include "relief/pattern_mesh.h"
#include "relief/procedural.h"

namespace rl {

ReliefImageSource image_source(const ReliefSourceDesc& relief) {
  ReliefImageSource src;
  src.normal_path = relief.normal_path;
  src.depth_path = relief.depth_path;
  src.color_path = relief.color_path;
  src.height_convention = relief.height_convention;
  src.flip_green = relief.flip_green;
  src.normalize = relief.normalize;
  src.nodata = relief.nodata;
  return src;
}

BakeFrame relief_bake_frame(const ReliefSourceDesc& relief, const TriangleMesh& mesh) {
  // A cell complex and a heightfield object live in the mesh's bounding cube: one scale on all
  // three axes.
  if (relief.cells.active || relief.faces > 0) return cell_frame(mesh, relief.mesh_up);
  const double margin = 0.04;  // of the footprint, each side
  BakeFrame f = bake_frame(mesh, relief.mesh_up, margin, relief.layers > 0 ? 0.02 : 0.0);
  if (relief.three_views) {
    // One quad size for the three bakes, the longest extent's: at one camera distance each
    // draws the object at one scale, so a view drawn from any of them frames it alike.
    // The footprint of the mesh's bounding cube, as a cell complex has it; the depth stays
    // this axis's own.
    const BakeFrame cube = cell_frame(mesh, relief.mesh_up, margin);
    f.side = cube.side;
    f.origin[f.axis_u] = cube.origin[f.axis_u];
    f.origin[f.axis_v] = cube.origin[f.axis_v];
  }
  return f;
}

TriangleMesh layered_tile_mesh(const SceneDesc& scene) {
  const ReliefSourceDesc& relief = scene.relief;
  if (relief.pattern_mesh())
    return make_pattern_mesh(relief.procedural, relief.options, "scene '" + scene.name + "'");
  TriangleMesh mesh = load_mesh(relief.mesh_path);
  const BakeFrame frame = relief_bake_frame(relief, mesh);
  for (glm::vec3& p : mesh.positions) {
    const glm::dvec3 t = frame.texture_from_mesh(glm::dvec3(p));
    p = glm::vec3(t.x, t.y, -t.z);
  }
  return mesh;
}

namespace {

// The complex of `mesh` (in texture space) with `options`, through the precompute cache, keyed
// by the mesh file's content and every option that changes the answer: a size entry, then the
// complex (CellComplex::serialize); a missing, foreign or corrupt entry is rebuilt. Bump the
// key's version whenever the construction changes its answer.
CellComplex cached_cell_complex(const ReliefSourceDesc& relief, TriangleMesh mesh,
                                const CellComplexOptions& o) {
  const uint64_t hash = file_content_hash(relief.mesh_path);
  char key[256];
  std::snprintf(key, sizeof key,
                "cell-complex v1 up=%d subdivide=%d grid=%d res=%d bits=%d threshold=%.17g "
                "grid_max=%d",
                relief.mesh_up, relief.cells.subdivide, o.grid, o.resolution, o.distance_bits,
                o.threshold, o.grid_max);
  const std::string folder = precompute_cache_dir(), size_key = std::string(key) + " size";
  uint64_t size = 0;
  if (read_precompute_cache(folder, size_key, hash, &size, sizeof size) && size < (1ull << 32)) {
    std::vector<uint8_t> bytes(size);
    CellComplex cc;
    if (read_precompute_cache(folder, key, hash, bytes.data(), bytes.size()) &&
        CellComplex::deserialize(bytes, mesh, cc))
      return cc;
  }
  CellComplex cc = CellComplex::build(mesh, o);
  const std::vector<uint8_t> bytes = cc.serialize();
  write_precompute_cache(folder, key, hash, bytes.data(), bytes.size());
  size = bytes.size();
  write_precompute_cache(folder, size_key, hash, &size, sizeof size);
  return cc;
}

// A cell complex of the relief's mesh, faces `resolution` texels square (0: native). The map
// itself is a flat placeholder of that size in the neutral albedo (what the truth shades a
// colourless mesh with); the complex is what the GPU gets (GpuRelief).
ReliefMap build_cell_complex_asset(const ReliefSourceDesc& relief, int resolution) {
  const TriangleMesh mesh =
      subdivide_midpoints(load_mesh(relief.mesh_path), relief.cells.subdivide);
  const int res = resolution > 0 ? resolution : relief.native.width;
  CellComplexOptions options;
  options.grid = relief.cells.grid;
  options.resolution = res;
  options.distance_bits = relief.cells.distance_bits;
  options.threshold = relief.cells.threshold;
  options.grid_max = relief.cells.grid_max;
  ReliefMap map;
  map.name = mesh.name;
  map.width = map.height = res;
  map.relief.assign(size_t(res) * res, glm::vec4(0.5f, 0.5f, 1.0f, 0.0f));
  map.color.assign(size_t(res) * res, glm::vec4(kCellAlbedo, 1.0f));
  map.cells = std::make_shared<const CellComplex>(
      cached_cell_complex(relief, to_frame(mesh, relief_bake_frame(relief, mesh)), options));
  return map;
}

// One heightfield or layered map from `relief` at `resolution`, before quantisation. `tiling`:
// how often it repeats per base tile (a meta-relief layer), which shrinks its texels on the
// base and so steepens the normals derived from its depth.
ReliefMap build_map(const SceneDesc& scene, const ReliefSourceDesc& relief, int resolution,
                    double tiling) {
  const PlanarBase base = planar_base(scene);
  const MapSize size = relief.size_at(resolution);
  ReliefMap map;
  if (!relief.mesh_path.empty()) {
    const TriangleMesh mesh = load_mesh(relief.mesh_path);
    const BakeFrame frame = relief_bake_frame(relief, mesh);
    if (relief.faces > 0) {
      // An object from several heightfields: the top face's map stands in as `relief`.
      auto faces = std::make_shared<HeightfieldFaces>(bake_heightfield_faces(
          mesh, frame, resolution, relief.faces, ReverseProjection{relief.reverse_cop}));
      if (scene.quantize)
        for (ReliefMap& m : faces->maps) quantize_8bit(m);
      map = faces->maps[0];
      map.faces = std::move(faces);
    } else if (relief.layers > 0)
      map = bake_layers(mesh, frame, resolution, resolution, relief.layers,
                        {glm::length(base.dpdu()), glm::length(base.dpdv()), scene.depth}, true,
                        relief.open_surface_gap);
    else
      map = bake_mesh(mesh, frame, resolution, scene.projection);
  } else if (relief.pattern_mesh()) {
    // Baked at the map's resolution; normals as seen on this scene's base.
    const TriangleMesh mesh =
        make_pattern_mesh(relief.procedural, relief.options, "scene '" + scene.name + "'");
    map = bake_layers(with_neighbour_tiles(mesh), pattern_frame(), size.width, size.height,
                      relief.layers,
                      {glm::length(base.dpdu()), glm::length(base.dpdv()), scene.depth});
  } else if (!relief.procedural.empty()) {
    map = make_procedural(relief.procedural, size.longer(), relief.options,
                          scene.depth * tiling / base.texel_world(size.longer()),
                          "scene '" + scene.name + "'");
  } else {
    // Normals from depth take the slope at the native texel size, before any resampling.
    const double native_texel = base.texel_world(relief.native.width);
    map = load_relief_images(image_source(relief), scene.depth * tiling / native_texel);
    map = resample(map, size.width, size.height);
  }
  return map;
}

}  // namespace

int meta_layer_resolution(const SceneDesc& scene, const MetaLayerDesc& layer, int resolution) {
  const double scale =
      double(scene.relief.size_at(resolution).longer()) / std::max(1, scene.relief.native.longer());
  return std::max(2, int(std::lround(layer.relief.native.longer() * scale)));
}

ReliefMap build_relief_asset(const SceneDesc& scene, int resolution) {
  return build_relief_asset(scene, resolution, scene.color_texture_res);
}

ReliefMap build_relief_asset(const SceneDesc& scene, int resolution, int color_resolution) {
  if (scene.cell_complex()) return build_cell_complex_asset(scene.relief, resolution);
  ReliefMap map = build_map(scene, scene.relief, resolution, 1.0);
  if (color_resolution > 0 &&
      scene.relief.size_at(color_resolution).longer() != std::max(map.width, map.height)) {
    // The colour of the same relief built at its own resolution (Section 4.3).
    const ReliefMap color = build_map(scene, scene.relief, color_resolution, 1.0);
    map.color = color.color;
    map.color_width = color.width;
    map.color_height = color.height;
  }
  if (scene.quantize) quantize_8bit(map);
  map.floor_color = scene.floor_color;
  if (!scene.meta.active()) return map;
  // A meta-relief: the sweep's resolution is layer 0's; every other layer is scaled by the same
  // factor from its native size (so "native" keeps each layer's own), each at its tiling.
  std::vector<MetaLayer> layers;
  layers.push_back({map, 1.0, scene.meta.weight_normal, scene.meta.weight_depth});
  for (const MetaLayerDesc& d : scene.meta.layers) {
    ReliefMap layer =
        build_map(scene, d.relief, meta_layer_resolution(scene, d, resolution), d.tiling);
    if (scene.quantize) quantize_8bit(layer);
    layers.push_back({std::move(layer), d.tiling, d.weight_normal, d.weight_depth});
  }
  auto meta = std::make_shared<const MetaRelief>(std::move(layers));
  const int longer =
      scene.meta.bake_resolution > 0 ? scene.meta.bake_resolution : std::max(map.width, map.height);
  const int bake_w =
      map.width >= map.height ? longer : std::max(1, longer * map.width / map.height);
  const int bake_h =
      map.width >= map.height ? std::max(1, longer * map.height / map.width) : longer;
  ReliefMap color;
  if (scene.meta.color_resolution > 0) {
    color = build_map(scene, scene.relief, scene.meta.color_resolution, 1.0);
    if (scene.quantize) quantize_8bit(color);
  }
  ReliefMap baked =
      bake_meta_relief(*meta, bake_w, bake_h, scene.meta.color_resolution > 0 ? &color : nullptr);
  if (scene.quantize) quantize_8bit(baked);
  baked.meta = std::move(meta);
  return baked;
}

AoMap attach_ao_map(ReliefMap& map, const SceneDesc& scene, double texel_world,
                    AoMapMethod method) {
  if (!scene.drawn_effects().has(Effect::AmbientOcclusion)) return {};
  AoMapOptions o;
  o.directions = scene.ao.directions;
  o.filter = scene.ao.filter;
  o.height_texels = scene.ao.depth_of_map(scene.depth) / texel_world;
  // `texel_world` is layer 0's texel for a meta-relief; its bake may have another size.
  const double layer0_width = map.meta ? map.meta->layers()[0].map.width : map.width;
  if (!map.meta || scene.meta.ao_combine == MetaReliefDesc::AoCombine::Bake) {
    o.height_texels *= map.width / layer0_width;
    AoMap ao = cached_ao_map(map, o, method);
    map.ambient_visibility = ao.visibility;
    return ao;
  }
  // A meta-relief: each layer's AO map at its share of the depth and its texel size on the
  // base, combined by product or minimum (Section IV-A) at the bake's texels.
  AoMap combined;
  combined.width = map.width;
  combined.height = map.height;
  combined.from_cache = true;
  std::vector<std::vector<float>> per_layer;
  for (size_t i = 0; i < map.meta->layers().size(); ++i) {
    const MetaLayer& l = map.meta->layers()[i];
    const double layer_texel = texel_world * layer0_width / (l.map.width * l.tiling);
    AoMapOptions lo = o;
    lo.height_texels = map.meta->depth_share(i) * scene.ao.depth_of_map(scene.depth) / layer_texel;
    AoMap ao = cached_ao_map(l.map, lo, method);
    combined.compute_ms += ao.compute_ms;
    combined.from_cache = combined.from_cache && ao.from_cache;
    per_layer.push_back(std::move(ao.visibility));
  }
  const auto start = std::chrono::steady_clock::now();
  combined.visibility =
      combine_ao_maps(*map.meta, per_layer, map.width, map.height,
                      scene.meta.ao_combine == MetaReliefDesc::AoCombine::Min ? AoCombine::Min
                                                                              : AoCombine::Product);
  combined.compute_ms += ms_since(start);
  map.ambient_visibility = combined.visibility;
  map.meta_ambient_visibility = std::move(per_layer);
  return combined;
}

}  // namespace rl
