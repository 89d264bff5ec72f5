#include "truth/pattern_base_truth.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/elapsed.h"
#include "core/embree_util.h"
#include "relief/relief_map.h"

namespace rl {

namespace {

// A point of a pattern triangle clipped to a base triangle: pattern space (u, v relative to
// the base triangle's tile, z = -depth).
using Polygon = std::vector<glm::dvec3>;

// Keeps the part of `poly` on the side of the uv line a -> b where the base triangle lies.
Polygon clip(const Polygon& poly, const glm::dvec2& a, const glm::dvec2& b, double side) {
  auto dist = [&](const glm::dvec3& p) {
    return side * ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x));
  };
  Polygon out;
  for (size_t i = 0; i < poly.size(); ++i) {
    const glm::dvec3 &p = poly[i], &q = poly[(i + 1) % poly.size()];
    const double dp = dist(p), dq = dist(q);
    if (dp >= 0) out.push_back(p);
    if ((dp >= 0) != (dq >= 0)) out.push_back(p + (q - p) * (dp / (dp - dq)));
  }
  return out;
}

// The pattern tile's triangles binned on a grid of 1/32 tile over [-1, 2]^2 (a tile pokes a
// little past [0, 1]^2).
class PatternBins {
 public:
  static constexpr int kCells = 96;  // over [-1, 2]
  static int cell_of(double x) {
    return std::clamp(int(std::floor((x + 1.0) * 32.0)), 0, kCells - 1);
  }
  explicit PatternBins(const TriangleMesh& pattern) : bins_(size_t(kCells) * kCells) {
    for (uint32_t t = 0; t < pattern.triangles.size(); ++t) {
      glm::dvec2 lo(1e300), hi(-1e300);
      for (int k = 0; k < 3; ++k) {
        const glm::dvec2 p(pattern.positions[pattern.triangles[t][k]]);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
      for (int j = cell_of(lo.y); j <= cell_of(hi.y); ++j)
        for (int i = cell_of(lo.x); i <= cell_of(hi.x); ++i)
          bins_[size_t(j) * kCells + i].push_back(t);
    }
  }
  const std::vector<uint32_t>& at(int i, int j) const { return bins_[size_t(j) * kCells + i]; }

 private:
  std::vector<std::vector<uint32_t>> bins_;
};

}  // namespace

// One base triangle and one tile of the pattern: a pattern point q (u, v in the tile, z =
// -depth) lands where the base triangle's barycentrics of (u, v) put it, positions and normals
// interpolated as drawn, and depth along the normal.
struct PatternBaseTruth::TileOnTriangle {
  const BaseMesh& base;
  glm::uvec3 tri;
  glm::dvec2 a, b, c;  // the triangle's uvs in the tile's frame
  double area, side, depth;
  glm::dvec2 shift;  // the tile's origin in uv

  void map(const glm::dvec3& q, glm::dvec3& world, glm::dvec3& n) const {
    const double w1 = ((q.x - a.x) * (c.y - a.y) - (q.y - a.y) * (c.x - a.x)) / area;
    const double w2 = ((b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x)) / area;
    const double w0 = 1 - w1 - w2;
    const glm::dvec3 p =
        w0 * base.position[tri.x] + w1 * base.position[tri.y] + w2 * base.position[tri.z];
    n = w0 * base.normal[tri.x] + w1 * base.normal[tri.y] + w2 * base.normal[tri.z];
    n = glm::length(n) > 0 ? glm::normalize(n) : base.normal[tri.x];
    world = p + n * (q.z * depth);  // z = -depth: inward along the normal
  }
};

// Pattern triangle t clipped to the base triangle and mapped onto it, as a fan of triangles.
void PatternBaseTruth::add_clipped(const TriangleMesh& pattern, uint32_t t,
                                   const TileOnTriangle& on) {
  Polygon poly;
  for (int k = 0; k < 3; ++k)
    poly.push_back(glm::dvec3(pattern.positions[pattern.triangles[t][k]]));
  poly = clip(poly, on.a, on.b, on.side);
  if (poly.size() >= 3) poly = clip(poly, on.b, on.c, on.side);
  if (poly.size() >= 3) poly = clip(poly, on.c, on.a, on.side);
  if (poly.size() < 3) return;
  const uint32_t first = uint32_t(positions_.size());
  for (const glm::dvec3& q : poly) {
    glm::dvec3 world, n;
    on.map(q, world, n);
    positions_.push_back(glm::vec3(world));
    base_normals_.push_back(glm::vec3(n));
    uvs_.push_back(glm::vec2(glm::dvec2(q) + on.shift));
  }
  for (uint32_t k = 1; k + 1 < poly.size(); ++k) {
    triangles_.emplace_back(first, first + k, first + k + 1);
    colors_.push_back(pattern.triangle_colors.empty() ? kLayeredFloorColor
                                                      : pattern.triangle_colors[t]);
    on_floor_.push_back(t >= first_floor_triangle_);
  }
}

namespace {

// The tile with the square at depth 1 (z = -1) appended in `floor_color`; every triangle
// coloured (the pattern's neutral where it has no colours).
TriangleMesh with_floor(TriangleMesh tile, const glm::vec3& floor_color) {
  if (tile.triangle_colors.empty())
    tile.triangle_colors.assign(tile.triangles.size(), kLayeredFloorColor);
  const uint32_t first = uint32_t(tile.positions.size());
  for (const glm::vec2 corner :
       {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)})
    tile.positions.emplace_back(corner, -1.0f);
  tile.triangles.emplace_back(first, first + 1, first + 2);
  tile.triangles.emplace_back(first, first + 2, first + 3);
  tile.triangle_colors.insert(tile.triangle_colors.end(), 2, floor_color);
  return tile;
}

}  // namespace

PatternBaseTruth::PatternBaseTruth(const TriangleMesh& tile_mesh, const BaseMesh& base,
                                   double depth, const std::optional<glm::vec3>& floor_color) {
  const auto start = std::chrono::steady_clock::now();
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("cannot create an Embree device");
  if (floor_color) first_floor_triangle_ = uint32_t(tile_mesh.triangles.size());
  const TriangleMesh pattern = floor_color ? with_floor(tile_mesh, *floor_color) : tile_mesh;
  const PatternBins bins(pattern);
  std::vector<uint64_t> stamp(pattern.triangles.size(), 0);  // a triangle's last visit
  uint64_t visits = 0;                                       // one per (base triangle, tile)
  // Each base triangle takes the pattern over its own uv triangle, clipped to it and mapped by
  // its barycentrics. Neighbouring base triangles clip at their shared edge, so the mapped
  // pattern has no cracks; a uv mapping that covers some uvs twice (a teapot's spout over its
  // body) simply gets the pattern twice, once on each part of the surface.
  for (uint32_t bt = 0; bt < base.triangles.size(); ++bt) {
    const glm::uvec3 tri = base.triangles[bt];
    const glm::dvec2 uv0 = base.uv[tri.x], uv1 = base.uv[tri.y], uv2 = base.uv[tri.z];
    const double area = (uv1.x - uv0.x) * (uv2.y - uv0.y) - (uv1.y - uv0.y) * (uv2.x - uv0.x);
    if (std::abs(area) < 1e-18) continue;  // collapsed in uv (a pole's row): nothing maps there
    const glm::dvec2 lo = glm::min(uv0, glm::min(uv1, uv2)), hi = glm::max(uv0, glm::max(uv1, uv2));
    // Every tile whose pattern may reach into the triangle, each tile once.
    for (int ty = int(std::floor(lo.y)) - 1; ty <= int(std::floor(hi.y)) + 1; ++ty)
      for (int tx = int(std::floor(lo.x)) - 1; tx <= int(std::floor(hi.x)) + 1; ++tx) {
        const glm::dvec2 shift(tx, ty);
        const glm::dvec2 qlo = glm::max(lo - shift, glm::dvec2(-1.0)),
                         qhi = glm::min(hi - shift, glm::dvec2(2.0));
        if (qlo.x > qhi.x || qlo.y > qhi.y) continue;
        const TileOnTriangle on{base,        tri,  uv0 - shift,           uv1 - shift,
                                uv2 - shift, area, area > 0 ? 1.0 : -1.0, depth,
                                shift};
        const uint64_t visit = ++visits;
        for (int j = PatternBins::cell_of(qlo.y); j <= PatternBins::cell_of(qhi.y); ++j)
          for (int i = PatternBins::cell_of(qlo.x); i <= PatternBins::cell_of(qhi.x); ++i)
            for (uint32_t t : bins.at(i, j))
              if (stamp[t] != visit) {
                stamp[t] = visit;
                add_clipped(pattern, t, on);
              }
      }
  }
  if (triangles_.empty()) throw std::runtime_error("pattern truth: no pattern on the base");
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
  h.geometric_normal = h.surface_normal;  // the flat triangle's: what rounding moves along
  h.normal =
      glm::normalize(b0 * glm::dvec3(base_normals_[t.x]) + b1 * glm::dvec3(base_normals_[t.y]) +
                     b2 * glm::dvec3(base_normals_[t.z]));
  h.albedo = glm::dvec3(colors_[rh.hit.primID]);
  // The floor is the underlying model: shaded with its normal, as the shaders shade a miss.
  if (on_floor_[rh.hit.primID])
    h.surface_normal = glm::dot(h.normal, direction) > 0 ? -h.normal : h.normal;
  return h;
}

bool PatternBaseTruth::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                                double t_max) const {
  ++shadow_rays_;
  return embree_occluded(scene_, origin, direction, t_min, t_max);
}

}  // namespace rl
