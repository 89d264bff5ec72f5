#pragma once
// Multilayer relief maps (Policarpo & Oliveira 2006, Sections 3 and 5): a closed mesh is
// sampled by parallel rays, one per texel centre, straight down through its bake box, and
// every crossing is kept -- depth, outward normal, colour -- up to `layers` per texel, sorted
// top to bottom, unused layers at depth 1. The map's single-layer view (`relief`, `color`) is
// the top layer, so heightfield techniques draw the same scene from its first surface.
#include <optional>

#include "relief/mesh_bake.h"
#include "relief/relief_map.h"

namespace rl {

// `world_scale`: world length of one unit of u, of v and of depth where the map is drawn; the
// stored normals are the mesh's normals as seen there (inverse transpose of that scaling), in
// the tangent frame the shaders shade with. Layer colours come from the mesh's triangle
// colours (neutral without). Crossings beyond `layers` are dropped and counted
// (LayerStack::overflow_texels); a mesh whose winding disagrees with the crossing order is
// oriented by the order (even layers enter the solid, odd ones leave it). `close_open`: a
// texel with an odd number of crossings (an open mesh) drops its deepest one, so its column
// gets a hole instead of a solid curtain down to the bottom (objects in a box, impostors).
// `open_surface_gap`: a crossing of an open surface (a connected part of the mesh with a
// boundary) is kept as two layers, entered and left this far apart in depth -- 0 for the
// paper's two coincident layers (Policarpo & Oliveira 2006, Section 7); without it such a
// surface is one crossing, which close_open drops.
ReliefMap bake_layers(const TriangleMesh& mesh, const BakeFrame& frame, int width, int height,
                      int layers, const glm::dvec3& world_scale, bool close_open = false,
                      std::optional<double> open_surface_gap = std::nullopt);

// The frame of a pattern mesh (relief/pattern_mesh.h), which is built in texture space.
BakeFrame pattern_frame();

}  // namespace rl
