#pragma once
// Objects from several heightfields (Baboud & Decoret 2006, Section 4.2; Oliveira et al.'s six
// relief textures on a bounding box; chapter 5's head from three relief texture maps): a mesh
// in its bounding cube, baked into one heightfield per chosen cube face, each looking inward
// (orthographically, or with a reverse perspective towards a centre of projection behind it).
//
// Every face's bake is a first hit, so the whole object lies behind each face's surface: the
// object the faces stand for is the intersection of their solids (a point is inside when every
// face that sees it has it behind its surface). That is the rule of chapter 5's Listing 5.2 for
// a front and a back map ("inside range"), carried to any set of faces. Taking the nearest of
// the faces' own hits instead would keep every face's false walls: a face extrudes what it
// sees down to the far side of the cube, which only the other faces carve away.
#include <vector>

#include <glm/glm.hpp>

#include "core/triangle_mesh.h"
#include "relief/mesh_bake.h"
#include "relief/relief_map.h"
#include "relief/reverse_projection.h"

namespace rl {

// Cube faces are numbered like the cell complex's: 2 * axis + side in the cube's texture space
// (u, v, depth), so 4 is the top (depth 0, the single bake's face) and 5 the bottom.
inline constexpr int kCubeFaces = 6;
inline constexpr int kTopFace = 4;

// The face sets a scene can ask for: 1 = the top; 2 = top and bottom (Listing 5.2's front and
// back maps); 3 = top, +u and +v (three bounding-box faces: the chapter's head); 6 = all.
// Throws std::invalid_argument for other counts.
std::vector<int> face_set(int count);

// The rotation of the cube's texture space about its centre that takes `face` to the top: its
// rows are the face map's u, v and depth axes in cube coordinates (depth along the inward
// normal), right-handed, the identity for the top.
glm::dmat3 face_from_cube(int face);

// Over-deep samples: a bake ray that missed the mesh stores depth 1; bilinear or 8-bit values
// at least this deep are an empty column (no surface, nothing behind it).
inline constexpr double kEmptyFaceDepth = 1.0 - 0.5 / 255.0;

struct HeightfieldFaces {
  std::vector<int> faces;        // cube face per map
  std::vector<ReliefMap> maps;   // per face: bake_mesh's map (normal in the face's u, v, up)
  ReverseProjection projection;  // of every face (each face's own box is the cube)

  int count() const { return int(faces.size()); }
  int resolution() const { return maps.empty() ? 0 : maps[0].width; }
  // A cube point's coordinates in face k's texture space (u, v, depth); u, v outside [0, 1]
  // where a reverse-perspective face does not see the point.
  glm::dvec3 face_texture(int k, const glm::dvec3& cube) const;
  // How far `cube` lies behind face k's surface in that face's depth units (>= 0: inside the
  // face's solid), sampled like the shaders (bilinear, clamped to the edge texels); +infinity
  // where the face does not see the point, -infinity over an empty column.
  double behind(int k, const glm::dvec3& cube) const;
  // Inside every face's solid (the object the faces stand for), with `tolerance` depth units of
  // slack for equality (the GPU's 8-bit depths).
  bool inside(const glm::dvec3& cube, double tolerance = 0) const;
  // The face that shades a hit at `cube` (the shaders' rule): of the faces it lies within a
  // texel of, the one whose stored normal faces it most.
  int surface_face(const glm::dvec3& cube) const;
  // A face's normal at `cube` in the cube's texture space (u, v, depth), unit length.
  glm::dvec3 cube_normal(int k, const glm::dvec3& cube) const;
  size_t bytes() const;  // relief + colour maps as uploaded (RGBA8 or RGBA32F each)
};

// Bakes `mesh` from each face of `count` (face_set) at resolution^2 in `cube`, a cube-shaped
// frame (cell_frame), with `projection` for every face.
HeightfieldFaces bake_heightfield_faces(const TriangleMesh& mesh, const BakeFrame& cube,
                                        int resolution, int count,
                                        const ReverseProjection& projection = {});

}  // namespace rl
