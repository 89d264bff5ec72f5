#include "truth/objects_truth.h"

#include <limits>
#include <stdexcept>

#include "core/embree_util.h"
#include "truth/truth_render.h"

namespace rl {

ObjectsTruth::ObjectsTruth(const std::vector<SceneObject>& objects)
    : mesh_(make_object_mesh(objects)) {
  if (mesh_.empty()) return;
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("cannot create an Embree device");
  TriangleMesh tm;
  tm.positions = mesh_.position;
  tm.triangles = mesh_.triangles;
  scene_ = embree_triangle_scene(device_, tm);
}

ObjectsTruth::~ObjectsTruth() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

ObjectHit ObjectsTruth::intersect(const glm::dvec3& origin, const glm::dvec3& direction,
                                  double t_max) const {
  ObjectHit h;
  if (!scene_) return h;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = embree_ray(origin, direction, 0.0,
                            std::min(t_max, double(std::numeric_limits<float>::max())));
  rtcIntersect1(scene_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  const glm::uvec3 t = mesh_.triangles[rh.hit.primID];
  const double w1 = rh.hit.u, w2 = rh.hit.v, w0 = 1 - w1 - w2;
  h.hit = true;
  h.t = rh.ray.tfar;
  h.position = origin + direction * h.t;
  // Interpolated vertex normals, as the rasteriser interpolates them.
  h.normal =
      glm::normalize(w0 * glm::dvec3(mesh_.normal[t.x]) + w1 * glm::dvec3(mesh_.normal[t.y]) +
                     w2 * glm::dvec3(mesh_.normal[t.z]));
  h.albedo = glm::dvec3(mesh_.albedo[t.x]);
  return h;
}

void write_object_pixel(GBuffer& g, size_t i, const ObjectHit& h, const SceneDesc& scene,
                        const glm::dvec3& view_dir, bool in_shadow) {
  const glm::dvec3 to_light = glm::normalize(scene.light_position - h.position);
  const glm::dvec3 c = shade(scene.material, h.albedo, h.normal, to_light, -view_dir, in_shadow);
  g.color[i] = glm::vec4(glm::vec3(c), 1.0f);
  g.position[i] = glm::vec4(glm::vec3(h.position), 1.0f);
  g.normal[i] = glm::vec4(glm::vec3(h.normal), in_shadow ? 1.0f : 0.0f);
  g.hit[i] = glm::vec4(0.0f, 0.0f, -1.0f, 0.0f);
  const glm::dvec3 ambient = scene.material.ambient * h.albedo;
  // Meshes traced as they are drawn: only Embree's rounding, at the scene's scale.
  const double bound = truth_hit_bound(0.0, TruthSurface::kEmbreeRounding * scene.size, h.normal,
                                       h.normal, h.normal, view_dir, h.position);
  g.aux[i] = glm::vec4(1.0f, 0.0f, float((ambient.x + ambient.y + ambient.z) / 3.0), float(bound));
}

}  // namespace rl
