#include "truth/pattern_base_truth.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/elapsed.h"
#include "core/embree_util.h"

namespace rl {

PatternBaseTruth::PatternBaseTruth(const TriangleMesh& tile_mesh, const BaseMesh& base, bool wrap_v,
                                   double depth) {
  const auto start = std::chrono::steady_clock::now();
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("cannot create an Embree device");
  // The base's triangles laid out in uv space: a ray straight down at (u, v) finds the
  // triangle holding that uv and its barycentrics.
  TriangleMesh flat;
  for (const glm::dvec2& uv : base.uv) flat.positions.emplace_back(float(uv.x), float(uv.y), 0.0f);
  flat.triangles = base.triangles;
  RTCScene uv_scene = embree_triangle_scene(device_, flat);
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  glm::dvec2 lo(1e300), hi(-1e300);
  for (const glm::dvec2& uv : base.uv) {
    lo = glm::min(lo, uv);
    hi = glm::max(hi, uv);
  }
  const glm::dvec2 span = hi - lo;
  glm::dvec3 base_normal(0);
  auto base_point = [&](glm::dvec2 uv, double d) {
    // Tubes poke a little across the uv domain's edges: wrap u (the seam), clamp v (poles).
    uv.x -= span.x * std::floor((uv.x - lo.x) / span.x);
    if (wrap_v) uv.y -= span.y * std::floor((uv.y - lo.y) / span.y);
    // Off the domain's outer edges, where a float ray could slip past the last triangle.
    uv = glm::clamp(uv, lo + 1e-5, hi - 1e-5);
    RTCRayHit rh = embree_ray(glm::dvec3(uv, 1.0), glm::dvec3(0, 0, -1), 0.0, 2.0);
    rtcIntersect1(uv_scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
      throw std::runtime_error("pattern truth: uv (" + std::to_string(uv.x) + ", " +
                               std::to_string(uv.y) + ") is on no base triangle");
    const glm::uvec3 t = base.triangles[rh.hit.primID];
    const double b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1 - b1 - b2;
    const glm::dvec3 p =
        b0 * base.position[t.x] + b1 * base.position[t.y] + b2 * base.position[t.z];
    glm::dvec3 n = b0 * base.normal[t.x] + b1 * base.normal[t.y] + b2 * base.normal[t.z];
    n = glm::length(n) > 0 ? glm::normalize(n) : base.normal[t.x];
    base_normal = n;
    return p - n * (d * depth);
  };
  for (int j = int(std::lround(lo.y)); j < int(std::lround(hi.y)); ++j)
    for (int i = int(std::lround(lo.x)); i < int(std::lround(hi.x)); ++i) {
      const uint32_t first = uint32_t(positions_.size());
      for (const glm::vec3& q : tile_mesh.positions) {  // pattern space: x = u, y = v, z = -depth
        const glm::dvec2 uv(i + q.x, j + q.y);
        positions_.push_back(glm::vec3(base_point(uv, -q.z)));
        base_normals_.push_back(glm::vec3(base_normal));
        uvs_.push_back(glm::vec2(uv));
      }
      for (const glm::uvec3& t : tile_mesh.triangles) triangles_.push_back(t + glm::uvec3(first));
      colors_.insert(colors_.end(), tile_mesh.triangle_colors.begin(),
                     tile_mesh.triangle_colors.end());
    }
  rtcReleaseScene(uv_scene);
  TriangleMesh world;
  world.positions = positions_;
  world.triangles = triangles_;
  scene_ = embree_triangle_scene(device_, world);
  build_ms_ = ms_since(start);
}

PatternBaseTruth::~PatternBaseTruth() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

DisplacedHit PatternBaseTruth::intersect(const glm::dvec3& origin, const glm::dvec3& direction,
                                         double t_max) const {
  ++primary_rays_;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh = embree_ray(origin, direction, 0.0, t_max);
  rtcIntersect1(scene_, &ctx, &rh);
  DisplacedHit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  const glm::uvec3 t = triangles_[rh.hit.primID];
  const double b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1 - b1 - b2;
  h.hit = true;
  h.t = rh.ray.tfar;
  h.position = origin + direction * h.t;
  h.uv = b0 * glm::dvec2(uvs_[t.x]) + b1 * glm::dvec2(uvs_[t.y]) + b2 * glm::dvec2(uvs_[t.z]);
  h.has_surface = true;
  glm::dvec3 n = glm::normalize(glm::dvec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
  h.surface_normal = glm::dot(n, direction) > 0 ? -n : n;
  h.normal =
      glm::normalize(b0 * glm::dvec3(base_normals_[t.x]) + b1 * glm::dvec3(base_normals_[t.y]) +
                     b2 * glm::dvec3(base_normals_[t.z]));
  h.albedo = colors_.empty() ? glm::dvec3(0.78, 0.74, 0.70) : glm::dvec3(colors_[rh.hit.primID]);
  return h;
}

bool PatternBaseTruth::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                                double t_max) const {
  ++shadow_rays_;
  return embree_occluded(scene_, origin, direction, t_min, t_max);
}

}  // namespace rl
