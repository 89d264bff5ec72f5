#include "truth/shell_sheets.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "core/embree_util.h"
#include "core/parallel.h"

namespace rl {
namespace {

// A grid vertex shared between base triangles: on the edge between welded vertices a < b, k
// steps of n from a (a corner: (a, a, 0)).
uint64_t shared_key(uint64_t a, uint64_t b, uint64_t k, int n) {
  if (a > b) {
    std::swap(a, b);
    k = uint64_t(n) - k;
  }
  return (a * 0x9E3779B97F4A7C15ull) ^ (b << 20) ^ k ^ (a << 42);
}

struct VertexRecipe {
  unsigned triangle;
  int from, to;   // corners of the triangle (from == to: a corner or an interior vertex)
  double f;       // fraction from `from` to `to`
  double b1, b2;  // an interior vertex's barycentrics
};

}  // namespace

size_t ShellSheets::local(int i, int j) const {
  return size_t(j) * size_t(n_ + 1) - size_t(j) * size_t(j - 1) / 2 + size_t(i);
}

ShellSheets::ShellSheets(const BasePrisms& prisms, const LeastDepth& least_depth, double depth,
                         double texels_per_sub_edge, size_t max_triangles)
    : prisms_(prisms) {
  double longest = 0, radius = 0;
  size_t usable = 0;
  for (unsigned t = 0; t < prisms.size(); ++t) {
    for (int c = 0; c < 3; ++c) radius = std::max(radius, glm::length(prisms.corner(t, c)));
    if (!prisms.usable(t)) continue;
    ++usable;
    // The longest edge in texels, at most: texel_world is the shortest texel over the edges.
    const double world = std::max({glm::length(prisms.corner(t, 1) - prisms.corner(t, 0)),
                                   glm::length(prisms.corner(t, 2) - prisms.corner(t, 0)),
                                   glm::length(prisms.corner(t, 2) - prisms.corner(t, 1))});
    longest = std::max(longest, world / prisms.texel_world(t));
  }
  const int cap =
      std::max(1, int(std::sqrt(double(max_triangles) / double(std::max<size_t>(1, usable)))));
  n_ = std::clamp(int(std::ceil(longest / texels_per_sub_edge)), 1, cap);
  margin_ = 1e-6 * std::max(radius, depth);
  number_vertices();
  place_vertices(least_depths(least_depth), depth);

  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("cannot create an Embree device");
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices_.data(),
                             0, sizeof(glm::vec3), vertices_.size());
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices_.data(), 0,
                             sizeof(glm::uvec3), indices_.size());
  attach_and_commit(scene_, geom);
}

ShellSheets::~ShellSheets() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

// Grid vertices, shared across base triangles on their common edges and corners; the sheet's
// triangles, n^2 per base triangle (up: (i, j), (i+1, j), (i, j+1); down: (i+1, j), (i+1, j+1),
// (i, j+1)), wound like the base triangle.
void ShellSheets::number_vertices() {
  const size_t per = local(0, n_) + 1;
  grid_.assign(prisms_.size() * per, 0);
  std::unordered_map<uint64_t, unsigned> shared;
  unsigned next = 0;
  auto id_for = [&](uint64_t key) {
    auto [it, added] = shared.emplace(key, next);
    if (added) ++next;
    return it->second;
  };
  for (unsigned t = 0; t < prisms_.size(); ++t) {
    const glm::uvec3& w = prisms_.welded(t);
    for (int j = 0; j <= n_; ++j)
      for (int i = 0; i + j <= n_; ++i) {
        unsigned id;
        if (i == 0 && j == 0)
          id = id_for(shared_key(w.x, w.x, 0, n_));
        else if (i == n_)
          id = id_for(shared_key(w.y, w.y, 0, n_));
        else if (j == n_)
          id = id_for(shared_key(w.z, w.z, 0, n_));
        else if (j == 0)
          id = id_for(shared_key(w.x, w.y, uint64_t(i), n_));
        else if (i == 0)
          id = id_for(shared_key(w.x, w.z, uint64_t(j), n_));
        else if (i + j == n_)
          id = id_for(shared_key(w.y, w.z, uint64_t(j), n_));
        else
          id = next++;
        grid_[t * per + local(i, j)] = id;
      }
  }
  vertices_.assign(next, glm::vec3(0));
  indices_.clear();
  indices_.reserve(prisms_.size() * size_t(n_) * size_t(n_));
  for (unsigned t = 0; t < prisms_.size(); ++t) {
    const unsigned* g = &grid_[t * per];
    for (int j = 0; j < n_; ++j)
      for (int i = 0; i + j < n_; ++i) {
        indices_.push_back({g[local(i, j)], g[local(i + 1, j)], g[local(i, j + 1)]});
        if (i + j + 1 < n_)
          indices_.push_back({g[local(i + 1, j)], g[local(i + 1, j + 1)], g[local(i, j + 1)]});
      }
  }
}

// Per sheet vertex: the least depth over the padded uv footprints of every sub-triangle that
// has it as a corner.
std::vector<double> ShellSheets::least_depths(const LeastDepth& least_depth) const {
  const size_t per_triangle = size_t(n_) * size_t(n_);
  std::vector<double> sub(prisms_.size() * per_triangle);
  parallel_for(
      prisms_.size(),
      [&](size_t begin, size_t end) {
        for (size_t t = begin; t < end; ++t) {
          size_t k = 0;
          for (int j = 0; j < n_; ++j)
            for (int i = 0; i + j < n_; ++i) {
              auto uv_at = [&](int a, int b) {
                return prisms_.uv(unsigned(t), double(a) / n_, double(b) / n_);
              };
              const glm::dvec2 p = uv_at(i, j), q = uv_at(i + 1, j), r = uv_at(i, j + 1);
              sub[t * per_triangle + k++] =
                  least_depth(glm::min(p, glm::min(q, r)), glm::max(p, glm::max(q, r)));
              if (i + j + 1 < n_) {
                const glm::dvec2 s = uv_at(i + 1, j + 1);
                sub[t * per_triangle + k++] =
                    least_depth(glm::min(q, glm::min(s, r)), glm::max(q, glm::max(s, r)));
              }
            }
        }
      },
      4);
  std::vector<double> least(vertices_.size(), std::numeric_limits<double>::infinity());
  for (size_t f = 0; f < indices_.size(); ++f)
    for (int c = 0; c < 3; ++c) least[indices_[f][c]] = std::min(least[indices_[f][c]], sub[f]);
  return least;
}

// Sheet vertex positions: P - (depth c - margin) N / |N|, computed once per vertex from the
// base's own corner data (bit-identical on every side of a shared edge).
void ShellSheets::place_vertices(const std::vector<double>& least, double depth) {
  const size_t per = local(0, n_) + 1;
  std::vector<char> placed(vertices_.size(), 0);
  for (unsigned t = 0; t < prisms_.size(); ++t) {
    const glm::uvec3& w = prisms_.welded(t);
    for (int j = 0; j <= n_; ++j)
      for (int i = 0; i + j <= n_; ++i) {
        const unsigned id = grid_[t * per + local(i, j)];
        if (placed[id]) continue;
        placed[id] = 1;
        const int edge_from = j == 0 ? 0 : (i == 0 ? 0 : 1);
        const int edge_to = j == 0 ? 1 : 2;
        const bool on_edge = (j == 0 || i == 0 || i + j == n_);
        glm::dvec3 p, n;
        if (on_edge) {
          // Canonical direction: from the corner with the smaller welded id.
          int from = edge_from, to = edge_to;
          double f = j == 0 ? double(i) / n_ : double(j) / n_;
          if (w[from] > w[to]) {
            std::swap(from, to);
            f = 1.0 - f;
          }
          p = prisms_.corner(t, from) * (1.0 - f) + prisms_.corner(t, to) * f;
          n = prisms_.corner_normal(t, from) * (1.0 - f) + prisms_.corner_normal(t, to) * f;
          if (f == 0.0) p = prisms_.corner(t, from), n = prisms_.corner_normal(t, from);
          if (f == 1.0) p = prisms_.corner(t, to), n = prisms_.corner_normal(t, to);
        } else {
          const double b1 = double(i) / n_, b2 = double(j) / n_;
          p = prisms_.corner(t, 0) * (1 - b1 - b2) + prisms_.corner(t, 1) * b1 +
              prisms_.corner(t, 2) * b2;
          n = prisms_.corner_normal(t, 0) * (1 - b1 - b2) + prisms_.corner_normal(t, 1) * b1 +
              prisms_.corner_normal(t, 2) * b2;
        }
        const double length = glm::length(n);
        if (length > 0) n /= length;
        vertices_[id] = glm::vec3(p - (depth * least[id] - margin_) * n);
      }
  }
}

glm::dvec3 ShellSheets::outward(const glm::uvec3& tri, const glm::dvec3& base_winding) const {
  const glm::dvec3 a(vertices_[tri.x]), b(vertices_[tri.y]), c(vertices_[tri.z]);
  return base_winding.x * glm::cross(b - a, c - a);
}

bool ShellSheets::entering(unsigned primitive, const glm::dvec3& direction) const {
  const glm::dvec3 winding(prisms_.winding(base_triangle(primitive)));
  return glm::dot(outward(indices_[primitive], winding), direction) < 0;
}

bool ShellSheets::outside(const glm::dvec3& x, const PrismPoint& p) const {
  // The sub-triangle over (b1, b2), clamped into the base triangle.
  const double u = std::clamp(p.b1, 0.0, 1.0) * n_, v = std::clamp(p.b2, 0.0, 1.0) * n_;
  int i = std::clamp(int(std::floor(u)), 0, n_ - 1), j = std::clamp(int(std::floor(v)), 0, n_ - 1);
  if (i + j > n_ - 1) i = n_ - 1 - j;
  const bool up = (u - i) + (v - j) <= 1.0 || i + j + 1 > n_ - 1;
  const size_t per_triangle = size_t(n_) * size_t(n_);
  // Sub-triangle index in the order number_vertices() emits them: row r holds 2 (n - r) - 1,
  // so the rows before j hold j (2 n - j).
  const size_t k = size_t(j) * size_t(2 * n_ - j) + size_t(2 * i) + (up ? 0 : 1);
  const glm::uvec3& tri = indices_[p.triangle * per_triangle + k];
  const glm::dvec3 n = outward(tri, glm::dvec3(prisms_.winding(p.triangle)));
  const double length = glm::length(n);
  if (!(length > 0)) return false;
  return glm::dot(x - glm::dvec3(vertices_[tri.x]), n / length) > margin_;
}

}  // namespace rl
