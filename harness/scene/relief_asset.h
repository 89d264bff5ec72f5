#pragma once
// Builds a scene's relief map at a texture resolution (its longer side; ReliefSourceDesc::
// size_at): procedural maps are generated at that resolution, image maps are loaded and
// resampled keeping their aspect; then quantised to 8 bits if the scene asks. A scene with a
// meta-relief gets the bake of its combination (relief/meta_relief.h) with the layers attached
// (map.meta): the resolution is layer 0's, the other layers scaled from their native sizes by
// the same factor; all with the scene's quantisation.
#include "relief/ao_map.h"
#include "relief/image_io.h"
#include "relief/mesh_bake.h"
#include "relief/relief_map.h"
#include "scene/scene.h"

namespace rl {

ReliefMap build_relief_asset(const SceneDesc& scene, int resolution);

// The longer side a meta-relief's `layer` is built at when the sweep asks for `resolution`
// (layer 0's): scaled from its native size by the factor that takes layer 0 from its own.
int meta_layer_resolution(const SceneDesc& scene, const MetaLayerDesc& layer, int resolution);
// The same with its colour map at `color_resolution` (longer side; 0: the map's own), as the
// truth's colour where the scene sets truth_color_resolution.
ReliefMap build_relief_asset(const SceneDesc& scene, int resolution, int color_resolution);

// Where the scene asks for ambient_occlusion, computes (or reads from the cache) the AO map of
// the relief as tall as scene.ao.map_depth (the scene's depth unless it is a rescale), with
// texels `texel_world` wide on the base (a meta-relief's layer 0), and stores it in
// map.ambient_visibility: for a meta-relief, its layers' maps combined (MetaReliefDesc::AoCombine)
// or the bake's own. Returns the
// map's timing; does nothing (and returns an empty AoMap) otherwise.
// `method`: who computes the maps (the CPU search by default).
AoMap attach_ao_map(ReliefMap& map, const SceneDesc& scene, double texel_world,
                    AoMapMethod method = {});

// The bake box of a mesh relief: the mesh's footprint, padded in depth too when it is baked
// into layers (an impostor). Used alike by the bake, the truth and the scene's depth.
BakeFrame relief_bake_frame(const ReliefSourceDesc& relief, const TriangleMesh& mesh);

// The tile a layered relief repeats over a curved base, in pattern space (x = u, y = v,
// z = -depth: relief/pattern_mesh.h): the procedural pattern, or the mesh file where its bake
// frame puts it (one object per tile, as the layers hold it).
TriangleMesh layered_tile_mesh(const SceneDesc& scene);

// The image files and conventions of an image relief, as load_relief_images takes them.
ReliefImageSource image_source(const ReliefSourceDesc& relief);

}  // namespace rl
