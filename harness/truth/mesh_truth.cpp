#include "truth/mesh_truth.h"

#include <chrono>

#include "core/embree_util.h"

namespace rl {

MeshTruth::MeshTruth(const TriangleMesh& mesh, const BakeFrame& frame) {
  const auto start = std::chrono::steady_clock::now();
  device_ = rtcNewDevice(nullptr);
  scene_ = embree_triangle_scene(device_, mesh,
                                 [&](const glm::dvec3& p) { return frame.texture_from_mesh(p); });
  build_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

MeshTruth::~MeshTruth() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

TruthHit MeshTruth::intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                              double t_max) const {
  ++primary_rays_;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh = embree_ray(origin, direction, t_min, t_max);
  rtcIntersect1(scene_, &ctx, &rh);
  TruthHit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.hit = true;
  h.t = rh.ray.tfar;
  h.point = origin + direction * h.t;
  h.has_normal = true;
  h.normal = glm::normalize(glm::dvec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
  if (glm::dot(h.normal, direction) > 0) h.normal = -h.normal;  // face the ray
  return h;
}

bool MeshTruth::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                         double t_max) const {
  ++shadow_rays_;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh = embree_ray(origin, direction, t_min, t_max);
  rtcOccluded1(scene_, &ctx, &rh.ray);
  return rh.ray.tfar < 0;
}

}  // namespace rl
