#include "truth/heightfield_truth.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/elapsed.h"
#include "core/embree_util.h"
#include "core/grid_walk.h"
#include "core/parallel.h"

namespace rl {

double max_twist(const ReliefMap& map) {
  double m = 0;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x)
      m = std::max(m, std::abs(double(map.depth_texel(x, y)) - map.depth_texel(x + 1, y) -
                               map.depth_texel(x, y + 1) + map.depth_texel(x + 1, y + 1)));
  return m;
}

namespace {

void embree_error(void*, RTCError code, const char* message) {
  throw std::runtime_error("Embree error " + std::to_string(int(code)) + ": " +
                           (message ? message : ""));
}

}  // namespace

HeightfieldTruth::HeightfieldTruth(const ReliefMap& map, double tolerance, size_t max_vertices,
                                   int forced_subdivision) {
  const auto start = std::chrono::steady_clock::now();
  const double twist = max_twist(map);
  const int max_k = std::max(
      1, static_cast<int>(std::sqrt(double(max_vertices)) / std::max(map.width, map.height)));
  const int needed = twist > 0 ? int(std::ceil(std::sqrt(twist / (4 * tolerance)))) : 1;
  subdivision_ = forced_subdivision > 0 ? forced_subdivision : std::clamp(needed, 1, max_k);
  bound_ = twist / (4.0 * subdivision_ * subdivision_);
  max_depth_ = map.max_depth();
  offset_ = glm::dvec2(0.5 / map.width, 0.5 / map.height);

  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("cannot create an Embree device");
  rtcSetDeviceErrorFunction(device_, embree_error, nullptr);
  scene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);

  const int nu = map.width * subdivision_ + 1, nv = map.height * subdivision_ + 1;
  RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_GRID);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), size_t(nu) * nv));
  const int k = subdivision_;
  parallel_for(
      size_t(nv),
      [&](size_t begin, size_t end) {
        for (size_t b = begin; b < end; ++b) {
          for (int a = 0; a < nu; ++a) {
            // Vertex (a, b) lies in texel-centre coordinates at (a / k, b / k): exactly on the
            // crease lines every k vertices. Depth is the bilinear sample there.
            const double u = offset_.x + double(a) / (double(k) * map.width);
            const double v = offset_.y + double(b) / (double(k) * map.height);
            float* p = vertices + 3 * (b * size_t(nu) + a);
            p[0] = float(u);
            p[1] = float(v);
            p[2] = float(map.sample_depth(u, v));
          }
        }
      },
      16);
  // Grids are limited to 32767 vertices a side; split into bands if needed.
  const int band = 32766;
  std::vector<RTCGrid> grids;
  for (int v0 = 0; v0 < nv - 1; v0 += band)
    for (int u0 = 0; u0 < nu - 1; u0 += band) {
      RTCGrid g;
      g.startVertexID = unsigned(v0 * nu + u0);
      g.stride = unsigned(nu);
      g.width = static_cast<unsigned short>(std::min(band, nu - 1 - u0) + 1);
      g.height = static_cast<unsigned short>(std::min(band, nv - 1 - v0) + 1);
      grids.push_back(g);
    }
  auto* grid_buffer = static_cast<RTCGrid*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_GRID, 0, RTC_FORMAT_GRID, sizeof(RTCGrid), grids.size()));
  std::copy(grids.begin(), grids.end(), grid_buffer);
  attach_and_commit(scene_, geom);
  build_ms_ = ms_since(start);
}

HeightfieldTruth::~HeightfieldTruth() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

TruthHit HeightfieldTruth::intersect(const glm::dvec3& origin, const glm::dvec3& direction,
                                     double t_min, double t_max) const {
  ++primary_rays_;
  TruthHit result;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  walk_tiles(origin, direction, t_min, t_max, offset_,
             [&](const glm::dvec3& local, double t0, double t1) {
               RTCRayHit rh = embree_ray(local, direction, t0, t1);
               rtcIntersect1(scene_, &context, &rh);
               if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
               result.hit = true;
               result.t = rh.ray.tfar;
               result.point = origin + direction * result.t;
               return true;
             });
  return result;
}

bool HeightfieldTruth::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                                double t_max) const {
  ++shadow_rays_;
  return walk_tiles(origin, direction, t_min, t_max, offset_,
                    [&](const glm::dvec3& local, double t0, double t1) {
                      return embree_occluded(scene_, local, direction, t0, t1);
                    });
}

}  // namespace rl
