#include "scene/relief_asset.h"

#include "relief/image_io.h"
#include "relief/layer_bake.h"
#include "relief/mesh_bake.h"
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
  return src;
}

BakeFrame relief_bake_frame(const ReliefSourceDesc& relief, const TriangleMesh& mesh) {
  return bake_frame(mesh, relief.mesh_up, 0.04, relief.layers > 0 ? 0.02 : 0.0);
}

ReliefMap build_relief_asset(const SceneDesc& scene, int resolution) {
  const PlanarBase base = planar_base(scene);
  const MapSize size = scene.relief.size_at(resolution);
  ReliefMap map;
  if (!scene.relief.mesh_path.empty()) {
    const TriangleMesh mesh = load_mesh(scene.relief.mesh_path);
    const BakeFrame frame = relief_bake_frame(scene.relief, mesh);
    if (scene.relief.layers > 0)
      map = bake_layers(mesh, frame, resolution, resolution, scene.relief.layers,
                        {glm::length(base.dpdu()), glm::length(base.dpdv()), scene.depth}, true);
    else
      map = bake_mesh(mesh, frame, resolution, scene.projection);
  } else if (scene.relief.pattern_mesh()) {
    // Baked at the map's resolution; normals as seen on this scene's base.
    const TriangleMesh mesh = make_pattern_mesh(scene.relief.procedural, scene.relief.options,
                                                "scene '" + scene.name + "'");
    map = bake_layers(with_neighbour_tiles(mesh), pattern_frame(), size.width, size.height,
                      scene.relief.layers,
                      {glm::length(base.dpdu()), glm::length(base.dpdv()), scene.depth});
  } else if (!scene.relief.procedural.empty()) {
    map = make_procedural(scene.relief.procedural, resolution, scene.relief.options,
                          scene.depth / base.texel_world(resolution), "scene '" + scene.name + "'");
  } else {
    // Normals from depth take the slope at the native texel size, before any resampling.
    const double native_texel = base.texel_world(scene.relief.native.width);
    map = load_relief_images(image_source(scene.relief), scene.depth / native_texel);
    map = resample(map, size.width, size.height);
  }
  if (scene.quantize) quantize_8bit(map);
  return map;
}

AoMap attach_ao_map(ReliefMap& map, const SceneDesc& scene, double texel_world) {
  if (!scene.effects.has(Effect::AmbientOcclusion)) return {};
  AoMapOptions o;
  o.directions = scene.ao.directions;
  o.filter = scene.ao.filter;
  o.height_texels = scene.ao.depth_of_map(scene.depth) / texel_world;
  AoMap ao = cached_ao_map(map, o);
  map.ambient_visibility = ao.visibility;
  return ao;
}

}  // namespace rl
