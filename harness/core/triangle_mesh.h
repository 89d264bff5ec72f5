#pragma once
// A triangle mesh as loaded from a file: the lowest layer's geometry, shared by the mesh bake
// (relief/), base meshes (scene/), the truths and Embree helpers (core/).
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace rl {

struct TriangleMesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> uvs;  // per position when every part of the file has them, else empty
  std::vector<glm::uvec3> triangles;
  std::vector<glm::vec3> triangle_colors;  // per triangle albedo, or empty (neutral)
  glm::dvec3 lo{0}, hi{0};                 // bounding box
};

// Loads an OBJ or PLY file through Assimp, triangulated, as one mesh. Throws ConfigError
// naming the file if it cannot be read, holds no triangles, or is non-finite, out of range
// (beyond 1e15), malformed or degenerate. The same file with the same bytes, loaded again in
// the process, comes from memory.
TriangleMesh load_mesh(const std::string& path);

// One id per distinct vertex position, per vertex: a file may split a vertex by uv or normal.
std::vector<uint32_t> welded_vertex_ids(const TriangleMesh& mesh);

// How far a mesh is from closing a solid: its edges (vertices welded by position, since a file
// may split a vertex by uv or normal) used by one triangle only (a hole's rim) and by more
// than two (non-manifold).
struct MeshClosure {
  long boundary_edges = 0, non_manifold_edges = 0;
  bool closed() const { return boundary_edges == 0 && non_manifold_edges == 0; }
};
MeshClosure mesh_closure(const TriangleMesh& mesh);

}  // namespace rl
