#include "scene/scene_objects.h"

#include <cmath>

#include "scene/base_mesh.h"

namespace rl {

ObjectMesh make_object_mesh(const std::vector<SceneObject>& objects) {
  ObjectMesh out;
  for (const SceneObject& o : objects) {
    // The object's shape as a base mesh of diameter 2 * radius (cube: half side = radius).
    BaseDesc desc;
    if (o.shape == "sphere" || o.shape == "cube") {
      desc.kind = o.shape;
      desc.segments = 48;
    } else {
      desc.kind = "file";
      desc.path = o.shape;
    }
    const double size = o.shape == "cube" ? 2 * std::sqrt(3.0) * o.radius : 2 * o.radius;
    const BaseMesh m = make_base_mesh(desc, size, 1.0, /*require_uvs=*/false);
    const unsigned first = unsigned(out.position.size());
    for (size_t i = 0; i < m.position.size(); ++i) {
      out.position.push_back(glm::vec3(m.position[i] + o.center));
      out.normal.push_back(glm::vec3(m.normal[i]));
      out.albedo.push_back(glm::vec3(o.albedo));
    }
    for (const glm::uvec3& t : m.triangles) out.triangles.push_back(t + glm::uvec3(first));
  }
  return out;
}

}  // namespace rl
