#pragma once
// Meshes as heightfields (Baboud & Decoret 2006, Section 3; book chapter 5, Figure 5.1): a
// mesh is baked into a single-layer relief map by orthographic ray casting (Embree) from the
// top of its bounding box: depth, normal and colour per texel.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/triangle_mesh.h"
#include "relief/relief_map.h"
#include "relief/reverse_projection.h"

namespace rl {

// The bake's box: the mesh's footprint, squared and padded by `margin` (a fraction of its
// side) so the border texels are floor, seen from `up` (0, 1, 2 = x, y, z).
// Texture space: u along axis_u, v along axis_v, depth = (top - position[up]) / height.
struct BakeFrame {
  int up = 1, axis_u = 2, axis_v = 0;
  glm::dvec3 origin{0};  // mesh-space point at (u, v, depth) = (0, 0, 0)
  double side = 1;       // mesh units per unit of u and v
  double height = 1;     // mesh units per unit of depth
  glm::dvec3 texture_from_mesh(const glm::dvec3& p) const;
  glm::dvec3 mesh_from_texture(const glm::dvec3& t) const;
  // A mesh-space normal as a normal of the texture-space surface (u, v, depth).
  glm::dvec3 texture_normal(const glm::dvec3& n) const;
};

// `depth_margin` pads the depth range likewise (a fraction of the height on each side): layers
// at depth 0 or 1 would be lost to 8-bit quantisation (1.0 marks an unused layer).
BakeFrame bake_frame(const TriangleMesh& mesh, int up, double margin = 0.04,
                     double depth_margin = 0.0);

// Bake at resolution^2: per texel centre a ray from the box top, straight down, or with a
// reverse projection towards its centre of projection (Section 4); the texture-space depth
// of the first hit (1 where the ray misses), its geometric normal (facing up) in the frame
// (u, v, up), and a neutral albedo.
// `face_from_box` bakes from another face of a cube-shaped frame (side == height): a rotation
// of the box's affine space about its centre that takes that face to the top, so the face's
// (u, v, depth) is face_from_box * (a - 0.5) + 0.5 for a box point a (relief/heightfield_faces.h);
// the normal is then in that face's (u, v, up).
ReliefMap bake_mesh(const TriangleMesh& mesh, const BakeFrame& frame, int resolution,
                    const ReverseProjection& projection = {},
                    const glm::dmat3& face_from_box = glm::dmat3(1.0));

}  // namespace rl
