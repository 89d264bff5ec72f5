#pragma once
// Procedural non-height-field patterns as closed triangle meshes, so their truth is the exact
// geometry (Policarpo & Oliveira 2006: the weave of Figure 5, the double helix of Figure 12).
// A pattern is one tile in texture space: x = u and y = v in [0, 1], z = -depth with depth in
// [0, 1]. Threads are tubes swept along periodic curves; a tube leaves the tile at u = 1 (or
// v = 1) exactly where its copy in the next tile enters, so the tiled pattern is closed and
// outward-oriented while each tile's mesh has open ends on the tile border.
#include <map>
#include <string>
#include <vector>

#include "core/triangle_mesh.h"

namespace rl {

// The kinds make_pattern_mesh knows ("weave", "helix").
const std::vector<std::string>& pattern_mesh_kinds();
bool is_pattern_mesh(const std::string& kind);
// The options each kind takes, with defaults (for `relieflab list` and config checks).
std::map<std::string, double> pattern_mesh_defaults(const std::string& kind);

// weave: `threads` threads per direction and tile (even), elliptical cross-section `width` x
// `thickness` (texture units), undulating by +-`amplitude` in depth over and under each other.
// helix: `strands` (1 or 2) tubes of radius `thickness` winding `turns` times per tile around
// an axis along u at v = depth = 0.5, at `radius` from it; `helices` axes side by side in v.
// `segments` samples along each curve and `sides` around each tube. Each triangle carries its
// thread's colour. Throws ConfigError naming `where` on unknown options or values that make
// threads intersect.
TriangleMesh make_pattern_mesh(const std::string& kind, std::map<std::string, double> options,
                               const std::string& where);

// The tile with its eight neighbours (copies shifted by whole tiles in u and v). A tube's end
// ring is tilted, so a little of each tile's geometry pokes across the border into the next
// tile: whatever traces rays within one tile (the layer bake, the tiled truth) needs the
// neighbours' geometry too.
TriangleMesh with_neighbour_tiles(const TriangleMesh& tile);

}  // namespace rl
