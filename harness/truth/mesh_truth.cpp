#include "truth/mesh_truth.h"

#include <chrono>

#include "core/elapsed.h"
#include "core/embree_util.h"
#include "core/grid_walk.h"

namespace rl {

MeshTruth::MeshTruth(const TriangleMesh& mesh, const BakeFrame& frame,
                     const ReverseProjection& projection, bool tiled)
    : colors_(mesh.triangle_colors), tiled_(tiled) {
  const auto start = std::chrono::steady_clock::now();
  device_ = rtcNewDevice(nullptr);
  scene_ = embree_triangle_scene(device_, mesh, [&](const glm::dvec3& p) {
    return projection.texture_from_affine(frame.texture_from_mesh(p));
  });
  // Normals in the affine space (the projection would bend them): render_truth maps those
  // to world with the base's scaling alone.
  for (const auto& tri : mesh.triangles) {
    const glm::dvec3 a = frame.texture_from_mesh(glm::dvec3(mesh.positions[tri.x]));
    const glm::dvec3 b = frame.texture_from_mesh(glm::dvec3(mesh.positions[tri.y]));
    const glm::dvec3 c = frame.texture_from_mesh(glm::dvec3(mesh.positions[tri.z]));
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double len = glm::length(n);
    affine_normals_.push_back(len > 0 ? n / len : glm::dvec3(0, 0, -1));
  }
  build_ms_ = ms_since(start);
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
  TruthHit h;
  auto query = [&](const glm::dvec3& local, double t0, double t1) {
    RTCRayHit rh = embree_ray(local, direction, t0, t1);
    rtcIntersect1(scene_, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    h.hit = true;
    h.t = rh.ray.tfar;
    h.point = origin + direction * h.t;
    h.has_normal = true;
    h.normal = affine_normals_[rh.hit.primID];  // oriented towards the viewer by render_truth
    if (!colors_.empty()) {
      h.has_albedo = true;
      h.albedo = glm::dvec3(colors_[rh.hit.primID]);
    }
    return true;
  };
  if (tiled_)
    walk_tiles(origin, direction, t_min, t_max, glm::dvec2(0), query);
  else
    query(origin, t_min, t_max);
  return h;
}

bool MeshTruth::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                         double t_max) const {
  ++shadow_rays_;
  auto query = [&](const glm::dvec3& local, double t0, double t1) {
    return embree_occluded(scene_, local, direction, t0, t1);
  };
  return tiled_ ? walk_tiles(origin, direction, t_min, t_max, glm::dvec2(0), query)
                : query(origin, t_min, t_max);
}

}  // namespace rl
