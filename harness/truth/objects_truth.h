#pragma once
// The scene's plain triangle-mesh objects (scene/scene_objects.h) in an Embree scene: the
// truth traces them with the relief and keeps the nearer hit per pixel.
#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "core/gbuffer.h"
#include "scene/scene_objects.h"

namespace rl {

struct ObjectHit {
  bool hit = false;
  double t = 0;
  glm::dvec3 position, normal, albedo;
};

class ObjectsTruth {
 public:
  explicit ObjectsTruth(const std::vector<SceneObject>& objects);
  ~ObjectsTruth();
  ObjectsTruth(const ObjectsTruth&) = delete;
  ObjectsTruth& operator=(const ObjectsTruth&) = delete;

  bool empty() const { return mesh_.empty(); }
  // Nearest object hit along the unit world ray within [0, t_max].
  ObjectHit intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_max) const;

 private:
  ObjectMesh mesh_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

// Writes an object hit into pixel i as the object shader does (harness/glsl/object.frag):
// shaded colour (in shadow or not: scene_shadows), position, normal with the shadow flag, and
// layer -1 in the hit channel (metrics tell objects from relief by it).
void write_object_pixel(GBuffer& g, size_t i, const ObjectHit& h, const SceneDesc& scene,
                        const glm::dvec3& view_dir, bool in_shadow = false);

}  // namespace rl
