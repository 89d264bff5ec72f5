#include "truth/displaced_truth.h"

#include "relief/meta_relief.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/elapsed.h"
#include "core/embree_util.h"
#include "core/parallel.h"
#include "truth/heightfield_truth.h"

namespace rl {
namespace {

// Grid coordinates over [lo, hi]: both ends and every line (m + 0.5 + q / k) / texels inside,
// so that texel-centre creases are grid lines and each cell lies in one bilinear patch.
std::vector<double> grid_lines(double lo, double hi, int texels, int k) {
  const double step = 1.0 / (double(texels) * k), offset = 0.5 / texels, eps = 1e-9 * step;
  std::vector<double> out = {lo};
  for (long i = long(std::floor((lo - offset) / step)) + 1;; ++i) {
    const double x = offset + double(i) * step;
    if (x >= hi - eps) break;
    if (x > lo + eps) out.push_back(x);
  }
  out.push_back(hi);
  return out;
}

glm::dvec3 displaced(const glm::dvec3& p, const glm::dvec3& n, const glm::dvec2& uv,
                     const ReliefMap& map, double depth) {
  return p - n * (depth * map.surface_depth(uv.x, uv.y));
}

// A point of the base mesh as the rasteriser sees it: triangle t at barycentrics (1 - b1 - b2,
// b1, b2), positions, normals, uvs and mapping axes interpolated linearly.
struct MeshPoint {
  glm::dvec3 position, normal, dpdu, dpdv;
  glm::dvec2 uv;
};

MeshPoint mesh_point(const BaseMesh& m, const glm::uvec3& t, double b1, double b2) {
  const double b0 = 1 - b1 - b2;
  auto mix = [&](const auto& a) { return b0 * a[t.x] + b1 * a[t.y] + b2 * a[t.z]; };
  MeshPoint p{mix(m.position), mix(m.normal), mix(m.dpdu), mix(m.dpdv), mix(m.uv)};
  p.normal = glm::length(p.normal) > 0 ? glm::normalize(p.normal) : m.normal[t.x];
  return p;
}

// The displaced point and the unit shading frame there.
void displaced_vertex(const MeshPoint& p, const ReliefMap& map, double depth, glm::vec3& position,
                      glm::vec3& tangent, glm::vec3& bitangent) {
  glm::dvec3 t, b;
  uv_frame(p.normal, p.dpdu, p.dpdv, t, b);
  position = glm::vec3(displaced(p.position, p.normal, p.uv, map, depth));
  tangent = glm::vec3(t);
  bitangent = glm::vec3(b);
}

// Where uv falls on a chart's segment grid (base/mesh_charts order: vertex (i, j) of chart c is
// first + j * (segments_u + 1) + i, quads split along (i, j)-(i + 1, j + 1)): its triangle and
// barycentrics.
void locate_on_chart(const SurfaceChart& c, unsigned first, const glm::dvec2& uv, glm::uvec3& tri,
                     double& b1, double& b2) {
  const double fu = (uv.x - c.uv_min.x) / (c.uv_max.x - c.uv_min.x) * c.segments_u;
  const double fv = (uv.y - c.uv_min.y) / (c.uv_max.y - c.uv_min.y) * c.segments_v;
  const int i = std::clamp(int(std::floor(fu)), 0, c.segments_u - 1);
  const int j = std::clamp(int(std::floor(fv)), 0, c.segments_v - 1);
  const double a = fu - i, b = fv - j;
  const unsigned row = unsigned(c.segments_u) + 1;
  const unsigned v00 = first + unsigned(j) * row + unsigned(i), v10 = v00 + 1, v01 = v00 + row,
                 v11 = v01 + 1;
  if (a >= b) {
    tri = {v00, v10, v11};  // (1 - a) P00 + (a - b) P10 + b P11
    b1 = a - b;
    b2 = b;
  } else {
    tri = {v00, v11, v01};  // (1 - b) P00 + a P11 + (b - a) P01
    b1 = a;
    b2 = b - a;
  }
}

}  // namespace

DisplacedTruth::DisplacedTruth(const BaseMesh& base, const ReliefMap& map, double depth,
                               double tolerance, size_t max_triangles) {
  const auto start = std::chrono::steady_clock::now();
  // Chart grids run along one map's crease lines; a meta-relief's layers have several, so its
  // base triangles are split uniformly and the deviation measured like a mesh base's.
  if (!base.charts.empty() && !map.meta)
    build_from_charts(base, map, depth, tolerance, max_triangles);
  else
    build_from_triangles(base, map, depth, tolerance, max_triangles);

  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("cannot create an Embree device");
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  // Embree reads vertex positions straight out of Vertex (the uv that follows pads the last).
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices_.data(),
                             offsetof(Vertex, position), sizeof(Vertex), vertices_.size());
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices_.data(), 0,
                             3 * sizeof(unsigned), indices_.size() / 3);
  attach_and_commit(scene_, geom);
  build_ms_ = ms_since(start);
}

DisplacedTruth::~DisplacedTruth() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

// One chart's displaced grid at grid lines u x v, two triangles a cell, appended to vertices_
// and indices_ (the chart's base vertices start at first_base); returns how far the surface's
// centre of a cell lies from the middle of the diagonal it is split along, at most.
double DisplacedTruth::tessellate_chart(const BaseMesh& base, const SurfaceChart& c,
                                        unsigned first_base, const std::vector<double>& u,
                                        const std::vector<double>& v, const ReliefMap& map,
                                        double depth) {
  const size_t nu = u.size(), nv = v.size(), first = vertices_.size();
  vertices_.resize(first + nu * nv);
  std::vector<double> row_worst(nv, 0.0);
  auto at = [&](const glm::dvec2& uv) {
    glm::uvec3 tri;
    double b1, b2;
    locate_on_chart(c, first_base, uv, tri, b1, b2);
    return mesh_point(base, tri, b1, b2);
  };
  parallel_for(
      nv,
      [&](size_t begin, size_t end) {
        for (size_t j = begin; j < end; ++j)
          for (size_t i = 0; i < nu; ++i) {
            const MeshPoint p = at({u[i], v[j]});
            Vertex& out = vertices_[first + j * nu + i];
            displaced_vertex(p, map, depth, out.position, out.tangent, out.bitangent);
            out.uv = glm::vec2(p.uv);
            out.normal = glm::vec3(p.normal);
          }
      },
      8);
  // The split along each cell's diagonal a-e meets the surface's centre at (a + e) / 2.
  parallel_for(
      nv - 1,
      [&](size_t begin, size_t end) {
        for (size_t j = begin; j < end; ++j)
          for (size_t i = 0; i + 1 < nu; ++i) {
            const MeshPoint p = at({0.5 * (u[i] + u[i + 1]), 0.5 * (v[j] + v[j + 1])});
            const glm::dvec3 mid =
                0.5 * (glm::dvec3(vertices_[first + j * nu + i].position) +
                       glm::dvec3(vertices_[first + (j + 1) * nu + i + 1].position));
            row_worst[j] = std::max(
                row_worst[j], glm::length(displaced(p.position, p.normal, p.uv, map, depth) - mid));
          }
      },
      8);
  for (size_t j = 0; j + 1 < nv; ++j)
    for (size_t i = 0; i + 1 < nu; ++i) {
      const unsigned a = unsigned(first + j * nu + i), b = a + 1, d = unsigned(a + nu), e = d + 1;
      indices_.insert(indices_.end(), {a, b, e, a, e, d});
    }
  return row_worst.empty() ? 0.0 : *std::max_element(row_worst.begin(), row_worst.end());
}

void DisplacedTruth::build_from_charts(const BaseMesh& base, const ReliefMap& map, double depth,
                                       double tolerance, size_t max_triangles) {
  // Grid lines: texel-centre creases (k per texel) and the base's segment edges, so each cell
  // lies in one bilinear patch and one base quad.
  auto lines = [&](double lo, double hi, int texels, int segments, int k) {
    std::vector<double> out = grid_lines(lo, hi, texels, k);
    for (int i = 1; i < segments; ++i) out.push_back(lo + (hi - lo) * i / segments);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end(),
                          [&](double x, double y) { return y - x < 1e-9 * (hi - lo); }),
              out.end());
    return out;
  };
  auto plan = [&](int k, std::vector<std::vector<double>>& us,
                  std::vector<std::vector<double>>& vs) {
    us.clear();
    vs.clear();
    size_t triangles = 0;
    for (const SurfaceChart& c : base.charts) {
      us.push_back(lines(c.uv_min.x, c.uv_max.x, map.width, c.segments_u, k));
      vs.push_back(lines(c.uv_min.y, c.uv_max.y, map.height, c.segments_v, k));
      triangles += 2 * (us.back().size() - 1) * (vs.back().size() - 1);
    }
    return triangles;
  };
  const double twist = max_twist(map);
  int k = twist > 0 ? std::max(1, int(std::ceil(std::sqrt(twist / (4 * tolerance))))) : 1;
  std::vector<std::vector<double>> us, vs;
  // The budget wins over the tolerance; the achieved bound is reported.
  for (size_t planned; k > 1 && (planned = plan(k, us, vs)) > max_triangles;)
    k = std::max(1, std::min(k - 1, int(k * std::sqrt(double(max_triangles) / planned))));
  for (;; k *= 2) {
    plan(k, us, vs);
    vertices_.clear();
    indices_.clear();
    double worst = 0;
    unsigned first_base = 0;  // the chart's first vertex in the base mesh
    for (size_t ci = 0; ci < base.charts.size(); ++ci) {
      const SurfaceChart& c = base.charts[ci];
      worst = std::max(worst, tessellate_chart(base, c, first_base, us[ci], vs[ci], map, depth));
      first_base += unsigned(c.segments_u + 1) * unsigned(c.segments_v + 1);
    }
    subdivision_ = k;
    bound_ = worst / depth;
    if (bound_ <= tolerance || plan(2 * k, us, vs) > max_triangles || k >= 64) return;
  }
}

void DisplacedTruth::build_from_triangles(const BaseMesh& base, const ReliefMap& map, double depth,
                                          double tolerance, size_t max_triangles) {
  double longest = 0;  // longest base edge, in texels (of a meta-relief's finest layer)
  const glm::dvec2 texels =
      map.meta ? glm::dvec2(map.meta->finest_texels()) : glm::dvec2(map.width, map.height);
  for (const glm::uvec3& t : base.triangles)
    for (int e = 0; e < 3; ++e) {
      const glm::dvec2 d = base.uv[t[(e + 1) % 3]] - base.uv[t[e]];
      longest = std::max(longest, glm::length(d * texels));
    }
  const size_t cap =
      std::max<size_t>(1, max_triangles / std::max<size_t>(1, base.triangles.size()));
  const int n_cap = std::max(1, int(std::sqrt(double(cap))));
  int n = std::clamp(int(std::ceil(longest)), 1, n_cap);
  for (;;) {
    vertices_.clear();
    indices_.clear();
    const size_t per = size_t(n + 1) * (n + 2) / 2;
    vertices_.resize(per * base.triangles.size());
    std::vector<double> tri_worst(base.triangles.size(), 0.0);
    auto local = [n](int i, int j) { return size_t(j) * (n + 1) - size_t(j) * (j - 1) / 2 + i; };
    parallel_for(
        base.triangles.size(),
        [&](size_t begin, size_t end) {
          for (size_t ti = begin; ti < end; ++ti) {
            const glm::uvec3& t = base.triangles[ti];
            for (int j = 0; j <= n; ++j)
              for (int i = 0; i + j <= n; ++i) {
                const MeshPoint p = mesh_point(base, t, double(i) / n, double(j) / n);
                Vertex& out = vertices_[ti * per + local(i, j)];
                displaced_vertex(p, map, depth, out.position, out.tangent, out.bitangent);
                out.uv = glm::vec2(p.uv);
                out.normal = glm::vec3(p.normal);
              }
            // Deviation at the centroid of every upward sub-triangle.
            for (int j = 0; j < n; ++j)
              for (int i = 0; i + j < n; ++i) {
                const MeshPoint p = mesh_point(base, t, (i + 1.0 / 3) / n, (j + 1.0 / 3) / n);
                const glm::dvec3 mid =
                    (glm::dvec3(vertices_[ti * per + local(i, j)].position) +
                     glm::dvec3(vertices_[ti * per + local(i + 1, j)].position) +
                     glm::dvec3(vertices_[ti * per + local(i, j + 1)].position)) /
                    3.0;
                tri_worst[ti] =
                    std::max(tri_worst[ti],
                             glm::length(displaced(p.position, p.normal, p.uv, map, depth) - mid));
              }
          }
        },
        16);
    for (size_t ti = 0; ti < base.triangles.size(); ++ti) {
      const unsigned o = unsigned(ti * per);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i + j < n; ++i) {
          const unsigned a = o + unsigned(local(i, j)), b = o + unsigned(local(i + 1, j)),
                         c = o + unsigned(local(i, j + 1));
          indices_.insert(indices_.end(), {a, b, c});
          if (i + j + 1 < n)
            indices_.insert(indices_.end(), {b, o + unsigned(local(i + 1, j + 1)), c});
        }
    }
    subdivision_ = n;
    bound_ = *std::max_element(tri_worst.begin(), tri_worst.end()) / depth;
    if (bound_ <= tolerance || 2 * n > n_cap) return;
    n *= 2;
  }
}

DisplacedHit DisplacedTruth::intersect(const glm::dvec3& origin, const glm::dvec3& direction,
                                       double t_max) const {
  ++primary_rays_;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  DisplacedHit h;
  // The relief is one-sided, as the shaders have it ("base seen from below: no relief"): a hit
  // on the sheet from behind (through an open mesh's gaps) is passed through.
  double t_min = 0;
  for (int pass = 0; pass < 64; ++pass) {
    RTCRayHit rh = embree_ray(origin, direction, t_min, t_max);
    rtcIntersect1(scene_, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
    const unsigned* tri = &indices_[3 * size_t(rh.hit.primID)];
    const double w1 = rh.hit.u, w2 = rh.hit.v, w0 = 1 - w1 - w2;
    const Vertex &a = vertices_[tri[0]], &b = vertices_[tri[1]], &c = vertices_[tri[2]];
    auto mix3 = [&](const glm::vec3& x, const glm::vec3& y, const glm::vec3& z) {
      return glm::normalize(w0 * glm::dvec3(x) + w1 * glm::dvec3(y) + w2 * glm::dvec3(z));
    };
    h.normal = mix3(a.normal, b.normal, c.normal);
    if (glm::dot(h.normal, direction) >= 0) {
      t_min = double(rh.ray.tfar) * (1 + 1e-6) + 1e-7;
      continue;
    }
    h.hit = true;
    h.t = rh.ray.tfar;
    h.position = origin + direction * h.t;
    h.uv = w0 * glm::dvec2(a.uv) + w1 * glm::dvec2(b.uv) + w2 * glm::dvec2(c.uv);
    h.tangent = mix3(a.tangent, b.tangent, c.tangent);
    h.bitangent = mix3(a.bitangent, b.bitangent, c.bitangent);
    const glm::dvec3 ng(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    if (glm::length(ng) > 0)
      h.geometric_normal = glm::dot(ng, direction) > 0 ? -glm::normalize(ng) : glm::normalize(ng);
    return h;
  }
  return h;
}

bool DisplacedTruth::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                              double t_max) const {
  ++shadow_rays_;
  return embree_occluded(scene_, origin, direction, t_min, t_max);
}

}  // namespace rl
