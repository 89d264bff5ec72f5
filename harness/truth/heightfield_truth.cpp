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
#include "core/wrap.h"
#include "relief/heightfield_reference.h"

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

// Float rounding of a lifted vertex (its u, v and depth stored in 32 bits, magnitudes below 2)
// and of Embree's arithmetic on it, as a depth error per unit of (1 + slope): eight ulps.
constexpr double kVertexRounding = 1e-6;
// A point must lie this far (depth units) above the lifted tessellation before Embree is asked
// where the ray enters it: well clear of float rounding, so Embree sees the ray start outside.
constexpr double kBandClearance = 1e-5;

double nan() {
  return std::numeric_limits<double>::quiet_NaN();
}

void embree_error(void*, RTCError code, const char* message) {
  throw std::runtime_error("Embree error " + std::to_string(int(code)) + ": " +
                           (message ? message : ""));
}

double bilinear(double d00, double d10, double d01, double d11, double x, double y) {
  return d00 + (d10 - d00) * x + (d01 - d00) * y + (d00 - d10 - d01 + d11) * x * y;
}

}  // namespace

double HeightfieldTruth::depth_at(long i, long j) const {
  return depth_[size_t(wrap_index(j, height_)) * width_ + size_t(wrap_index(i, width_))];
}

HeightfieldTruth::HeightfieldTruth(const ReliefMap& map, double band_tolerance, size_t max_vertices,
                                   int forced_subdivision)
    : width_(map.width), height_(map.height), depth_(map.depths()) {
  const auto start = std::chrono::steady_clock::now();
  const int W = width_, H = height_;
  max_depth_ = map.max_depth();
  offset_ = glm::dvec2(0.5 / W, 0.5 / H);

  // The subdivision that keeps the tessellation within band_tolerance of the most twisted
  // cell, as far as max_vertices allows.
  const double twist = max_twist(map);
  const int max_k = std::max(1, static_cast<int>(std::sqrt(double(max_vertices)) / std::max(W, H)));
  const int needed = twist > 0 ? int(std::ceil(std::sqrt(twist / (4 * band_tolerance)))) : 1;
  subdivision_ = forced_subdivision > 0 ? forced_subdivision : std::clamp(needed, 1, max_k);
  build_lifted_grid(bound_bands());
  build_ms_ = ms_since(start);
}

// Per bilinear cell: its twist, and how far its tessellation may lie from it once float
// rounding of the vertices (worse on steep cells: a vertex rounded sideways) is counted. Sets
// band_ and band_max_; returns each cell's lift.
std::vector<float> HeightfieldTruth::bound_bands() {
  const int W = width_, H = height_;
  const int k = subdivision_;
  std::vector<float> deviation(size_t(W) * H), lift(size_t(W) * H);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const double d00 = depth_at(i, j), d10 = depth_at(i + 1, j), d01 = depth_at(i, j + 1),
                   d11 = depth_at(i + 1, j + 1);
      const double slope = std::max(std::abs(d10 - d00), std::abs(d11 - d01)) * W +
                           std::max(std::abs(d01 - d00), std::abs(d11 - d10)) * H;
      const size_t c = size_t(j) * W + i;
      deviation[c] = float(std::abs(d00 - d10 - d01 + d11) / (4.0 * k * k));
      lift[c] = float(deviation[c] + kVertexRounding * (1.0 + slope));
    }
  // The band of a cell: how far below the lifted tessellation the surface can be there. The
  // tessellation of the cell deviates by `deviation`; its vertices were lifted by at most the
  // largest lift of the cells around (a vertex on a crease is lifted for both sides), and
  // rounded by as much again.
  band_.resize(size_t(W) * H);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      double around = 0;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
          around = std::max(
              around, double(lift[size_t(wrap_index(j + dj, H)) * W + wrap_index(i + di, W)]));
      const size_t c = size_t(j) * W + i;
      band_[c] = float(deviation[c] + 2.0 * around + kBandClearance);
      band_max_ = std::max(band_max_, double(band_[c]));
    }

  return lift;
}

// The lifted tessellation: every cell's bilinear surface at k x k vertices, each lowered by the
// largest lift of the cells it touches, as Embree grids.
void HeightfieldTruth::build_lifted_grid(const std::vector<float>& lift) {
  const int W = width_, H = height_, k = subdivision_;
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("cannot create an Embree device");
  rtcSetDeviceErrorFunction(device_, embree_error, nullptr);
  scene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);

  const int nu = W * k + 1, nv = H * k + 1;
  RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_GRID);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), size_t(nu) * nv));
  // The cells a vertex at tessellation index a touches along one axis: one inside a cell, two
  // on a crease (every k-th index).
  auto cells_of = [k](int a, int n, long out[2]) {
    out[0] = wrap_index(a / k, n);
    out[1] = a % k == 0 ? wrap_index(a / k - 1, n) : out[0];
  };
  parallel_for(
      size_t(nv),
      [&](size_t begin, size_t end) {
        for (size_t b = begin; b < end; ++b) {
          long cy[2];
          cells_of(int(b), H, cy);
          const long j = long(b) / k;
          const double fy = double(long(b) % k) / k;
          for (int a = 0; a < nu; ++a) {
            long cx[2];
            cells_of(a, W, cx);
            const long i = a / k;
            const double fx = double(a % k) / k;
            // Vertex (a, b) lies at texel-centre coordinates (a / k, b / k): on the crease
            // lines every k vertices, on the bilinear surface, then lifted.
            const double surface = bilinear(depth_at(i, j), depth_at(i + 1, j), depth_at(i, j + 1),
                                            depth_at(i + 1, j + 1), fx, fy);
            double up = 0;
            for (long y : cy)
              for (long x : cx) up = std::max(up, double(lift[size_t(y) * W + size_t(x)]));
            float* p = vertices + 3 * (b * size_t(nu) + a);
            p[0] = float(offset_.x + double(a) / (double(k) * W));
            p[1] = float(offset_.y + double(b) / (double(k) * H));
            p[2] = float(surface - up);
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
}

HeightfieldTruth::~HeightfieldTruth() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

bool HeightfieldTruth::above_band(const glm::dvec3& p) const {
  const double X = p.x * width_ - 0.5, Y = p.y * height_ - 0.5;
  const long i = long(std::floor(X)), j = long(std::floor(Y));
  const double surface = bilinear(depth_at(i, j), depth_at(i + 1, j), depth_at(i, j + 1),
                                  depth_at(i + 1, j + 1), X - double(i), Y - double(j));
  return p.z <
         surface - band_[size_t(wrap_index(j, height_)) * width_ + size_t(wrap_index(i, width_))];
}

double HeightfieldTruth::lifted_entry(const glm::dvec3& origin, const glm::dvec3& direction,
                                      double t0, double t1) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  double entry = nan();
  uint64_t queries = 0;
  walk_tiles(origin, direction, t0, t1, offset_, [&](const glm::dvec3& local, double a, double b) {
    RTCRayHit rh = embree_ray(local, direction, a, b);
    ++queries;
    rtcIntersect1(scene_, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    entry = rh.ray.tfar;
    return true;
  });
  embree_queries_ += queries;
  return entry;
}

double HeightfieldTruth::exact_walk(const glm::dvec3& o, const glm::dvec3& d, double t0,
                                    double t_max, double& resume) const {
  // Texel-centre coordinates: X = u * width - 0.5, so cell (i, j) = [i, i+1] x [j, j+1] holds
  // one bilinear patch.
  const double X0 = o.x * width_ - 0.5, Y0 = o.y * height_ - 0.5;
  const double dX = d.x * width_, dY = d.y * height_;
  double hit = nan();
  resume = t_max;
  uint64_t cells = 0;
  walk_grid_2d(X0, Y0, dX, dY, t0, t_max, [&](long i, long j, double t_enter, double t_exit) {
    ++cells;
    const double d00 = depth_at(i, j), d10 = depth_at(i + 1, j), d01 = depth_at(i, j + 1),
                 d11 = depth_at(i + 1, j + 1);
    const double s = bilinear_patch_hit(d00, d10, d01, d11, X0 + dX * t_enter - double(i),
                                        Y0 + dY * t_enter - double(j), o.z + d.z * t_enter, dX, dY,
                                        d.z, t_exit - t_enter);
    if (!std::isnan(s)) {
      hit = t_enter + s;
      return true;
    }
    if (!(t_exit > t0 && t_exit < t_max)) return false;
    // Where the ray leaves the cell: still in the band, or clear above it (Embree's turn)?
    const double x = std::clamp(X0 + dX * t_exit - double(i), 0.0, 1.0);
    const double y = std::clamp(Y0 + dY * t_exit - double(j), 0.0, 1.0);
    const double band =
        band_[size_t(wrap_index(j, height_)) * width_ + size_t(wrap_index(i, width_))];
    if (o.z + d.z * t_exit < bilinear(d00, d10, d01, d11, x, y) - band) {
      resume = t_exit;
      return true;
    }
    return false;
  });
  exact_cells_ += cells;
  return hit;
}

double HeightfieldTruth::first_hit(const glm::dvec3& o, const glm::dvec3& d, double t_min,
                                   double t_max) const {
  // Back off from Embree's entry by its float error: a millionth of the distance, and half a
  // texel cell along the ray (a thousandth of the depth for a ray straight down).
  const double back_cell =
      0.5 / (std::abs(d.x) * width_ + std::abs(d.y) * height_ + 1e3 * std::abs(d.z));
  double t = t_min;
  // Every round moves t forward by at least one texel cell of the ray; this bounds the loop
  // for any input, however degenerate.
  const long rounds = long(std::min(1e8, (std::abs(d.x) * width_ + std::abs(d.y) * height_) *
                                             std::max(0.0, t_max - t_min))) +
                      8;
  for (long round = 0; round < rounds && t <= t_max; ++round) {
    if (above_band(o + d * t)) {
      const double entry = lifted_entry(o, d, t, t_max);
      if (std::isnan(entry)) return nan();
      t = std::max(t, entry - 1e-6 * (1.0 + std::abs(entry)) - back_cell);
    }
    double resume = t_max;
    const double hit = exact_walk(o, d, t, t_max, resume);
    if (!std::isnan(hit)) return hit;
    if (!(resume < t_max && resume > t)) return nan();
    t = resume;
  }
  return nan();
}

TruthHit HeightfieldTruth::intersect(const glm::dvec3& origin, const glm::dvec3& direction,
                                     double t_min, double t_max) const {
  ++primary_rays_;
  return hit_at(origin, direction, first_hit(origin, direction, t_min, t_max));
}

bool HeightfieldTruth::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                                double t_max) const {
  ++shadow_rays_;
  return !std::isnan(first_hit(origin, direction, t_min, t_max));
}

}  // namespace rl
