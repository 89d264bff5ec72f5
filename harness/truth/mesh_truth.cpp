#include "truth/mesh_truth.h"

#include <chrono>

namespace rl {

MeshTruth::MeshTruth(const TriangleMesh& mesh, const BakeFrame& frame) {
  const auto start = std::chrono::steady_clock::now();
  device_ = rtcNewDevice(nullptr);
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                        RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                        mesh.positions.size()));
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::dvec3 t = frame.texture_from_mesh(glm::dvec3(mesh.positions[i]));
    for (int c = 0; c < 3; ++c) v[3 * i + c] = float(t[c]);
  }
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0,
                                                             RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                             mesh.triangles.size()));
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    for (int c = 0; c < 3; ++c) idx[3 * i + c] = mesh.triangles[i][c];
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene_, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene_);
  build_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

MeshTruth::~MeshTruth() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

namespace {

RTCRayHit make_ray(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1) {
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

}  // namespace

TruthHit MeshTruth::intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                              double t_max) const {
  ++primary_rays_;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh = make_ray(origin, direction, t_min, t_max);
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
  RTCRayHit rh = make_ray(origin, direction, t_min, t_max);
  rtcOccluded1(scene_, &ctx, &rh.ray);
  return rh.ray.tfar < 0;
}

}  // namespace rl
