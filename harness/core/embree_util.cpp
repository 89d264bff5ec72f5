#include "core/embree_util.h"

namespace rl {

RTCRayHit embree_ray(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1) {
  RTCRayHit rh{};
  rh.ray.org_x = float(o.x);
  rh.ray.org_y = float(o.y);
  rh.ray.org_z = float(o.z);
  rh.ray.dir_x = float(d.x);
  rh.ray.dir_y = float(d.y);
  rh.ray.dir_z = float(d.z);
  rh.ray.tnear = float(t0);
  rh.ray.tfar = float(t1);
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

bool embree_occluded(RTCScene scene, const glm::dvec3& o, const glm::dvec3& d, double t0,
                     double t1) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = embree_ray(o, d, t0, t1).ray;
  rtcOccluded1(scene, &context, &ray);
  return ray.tfar < 0;  // Embree sets tfar = -inf on occlusion
}

RTCScene embree_triangle_scene(RTCDevice device, const TriangleMesh& mesh,
                               const std::function<glm::dvec3(const glm::dvec3&)>& to_space) {
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                        RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                        mesh.positions.size()));
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::dvec3 p =
        to_space ? to_space(glm::dvec3(mesh.positions[i])) : glm::dvec3(mesh.positions[i]);
    for (int c = 0; c < 3; ++c) v[3 * i + c] = float(p[c]);
  }
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                             RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                             mesh.triangles.size()));
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    for (int c = 0; c < 3; ++c) idx[3 * i + c] = mesh.triangles[i][c];
  attach_and_commit(scene, geom);
  return scene;
}

void attach_and_commit(RTCScene scene, RTCGeometry geom) {
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
}

}  // namespace rl
