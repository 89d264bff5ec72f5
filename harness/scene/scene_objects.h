#pragma once
// The plain triangle-mesh objects of a scene (SceneDesc::objects), as one world-space mesh
// with per-vertex normals: the GPU draws exactly these triangles and the truth traces them,
// so visibility between objects and relief is compared like for like (chapter 5, Figure 5.20).
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace rl {

struct ObjectMesh {
  std::vector<glm::vec3> position, normal, albedo;  // per vertex
  std::vector<glm::uvec3> triangles;                // counter-clockwise seen from outside
  bool empty() const { return triangles.empty(); }
};

// Spheres (48 x 24 quads), cubes (flat faces), or mesh files fitted into the object's sphere.
ObjectMesh make_object_mesh(const std::vector<SceneObject>& objects);

}  // namespace rl
