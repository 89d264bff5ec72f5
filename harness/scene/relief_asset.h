#pragma once
// Builds a scene's relief map at a texture resolution (its longer side; ReliefSourceDesc::
// size_at): procedural maps are generated at that resolution, image maps are loaded and
// resampled keeping their aspect; then quantised to 8 bits if the scene asks.
#include "relief/image_io.h"
#include "relief/mesh_bake.h"
#include "relief/relief_map.h"
#include "scene/scene.h"

namespace rl {

ReliefMap build_relief_asset(const SceneDesc& scene, int resolution);

// The bake box of a mesh relief: the mesh's footprint, padded in depth too when it is baked
// into layers (an impostor). Used alike by the bake, the truth and the scene's depth.
BakeFrame relief_bake_frame(const ReliefSourceDesc& relief, const TriangleMesh& mesh);

// The image files and conventions of an image relief, as load_relief_images takes them.
ReliefImageSource image_source(const ReliefSourceDesc& relief);

}  // namespace rl
