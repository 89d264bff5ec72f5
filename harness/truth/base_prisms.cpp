#include "truth/base_prisms.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace rl {
namespace {

// Welded ids: one per group of vertices whose positions and normals agree to a billionth (uvs
// may differ: a seam; a generated sphere's seam positions differ in the last bits).
std::vector<unsigned> weld(const BaseMesh& base) {
  double radius = 0;
  for (const glm::dvec3& p : base.position) radius = std::max(radius, glm::length(p));
  const double cell = 1e-9 * std::max(radius, 1e-300);
  auto key = [&](const glm::ivec3& c) {
    return (uint64_t(uint32_t(c.x)) * 0x9E3779B97F4A7C15ull) ^ (uint64_t(uint32_t(c.y)) << 21) ^
           (uint64_t(uint32_t(c.z)) * 0xC2B2AE3D27D4EB4Full);
  };
  std::unordered_map<uint64_t, std::vector<unsigned>> grid;
  std::vector<unsigned> welded(base.position.size()), representative;
  for (size_t v = 0; v < base.position.size(); ++v) {
    const glm::dvec3 p = base.position[v];
    const glm::ivec3 c(glm::floor(p / cell));
    int found = -1;
    for (int dz = -1; dz <= 1 && found < 0; ++dz)
      for (int dy = -1; dy <= 1 && found < 0; ++dy)
        for (int dx = -1; dx <= 1 && found < 0; ++dx) {
          const auto it = grid.find(key(c + glm::ivec3(dx, dy, dz)));
          if (it == grid.end()) continue;
          for (unsigned w : it->second) {
            const size_t r = representative[w];
            if (glm::length(base.position[r] - p) <= cell &&
                glm::length(base.normal[r] - base.normal[v]) <= 1e-9) {
              found = int(w);
              break;
            }
          }
        }
    if (found < 0) {
      found = int(representative.size());
      representative.push_back(unsigned(v));
      grid[key(c)].push_back(unsigned(found));
    }
    welded[v] = unsigned(found);
  }
  return welded;
}

}  // namespace

BasePrisms::BasePrisms(const BaseMesh& base, const glm::dvec2& texels) {
  const std::vector<unsigned> welded_of = weld(base);
  prisms_.resize(base.triangles.size());
  for (size_t t = 0; t < base.triangles.size(); ++t) {
    const glm::uvec3& tri = base.triangles[t];
    Prism& p = prisms_[t];
    p.p0 = base.position[tri.x];
    p.e1 = base.position[tri.y] - p.p0;
    p.e2 = base.position[tri.z] - p.p0;
    p.n0 = base.normal[tri.x];
    p.m1 = base.normal[tri.y] - p.n0;
    p.m2 = base.normal[tri.z] - p.n0;
    p.uv0 = base.uv[tri.x];
    p.duv1 = base.uv[tri.y] - p.uv0;
    p.duv2 = base.uv[tri.z] - p.uv0;
    p.welded = {welded_of[tri.x], welded_of[tri.y], welded_of[tri.z]};
    for (int c = 0; c < 3; ++c) {
      p.corner[c] = base.position[tri[c]];
      p.corner_normal[c] = base.normal[tri[c]];
      p.dpdu[c] = base.dpdu[tri[c]];
      p.dpdv[c] = base.dpdv[tri[c]];
    }
    p.winding = glm::dot(glm::cross(p.e1, p.e2),
                         p.corner_normal[0] + p.corner_normal[1] + p.corner_normal[2]) >= 0
                    ? 1.0
                    : -1.0;
    const double area = glm::length(glm::cross(p.e1, p.e2));
    const double scale = std::max(glm::length(p.e1), glm::length(p.e2));
    p.extent = std::max(scale, glm::length(p.e2 - p.e1));
    const glm::dmat3 flat(p.e1, p.e2, -p.n0);
    p.usable = area > 1e-12 * scale * scale && std::abs(glm::determinant(flat)) > 1e-14 * area;
    if (!p.usable) continue;
    p.flat_inverse = glm::inverse(flat);
    double shortest = 0;
    const glm::dvec3 world[3] = {p.e1, p.e2, p.e2 - p.e1};
    const glm::dvec2 tex[3] = {p.duv1, p.duv2, p.duv2 - p.duv1};
    for (int e = 0; e < 3; ++e) {
      const double in_texels = glm::length(tex[e] * texels);
      if (in_texels <= 0) continue;
      const double per_texel = glm::length(world[e]) / in_texels;
      shortest = shortest > 0 ? std::min(shortest, per_texel) : per_texel;
    }
    p.texel_world = shortest > 0 ? shortest : scale;
  }
  link_neighbours();
}

void BasePrisms::link_neighbours() {
  // Edge opposite vertex e joins the other two; an edge two usable prisms share links them.
  std::unordered_map<uint64_t, std::vector<std::pair<unsigned, int>>> edges;
  for (unsigned t = 0; t < prisms_.size(); ++t) {
    if (!prisms_[t].usable) continue;
    const glm::uvec3& w = prisms_[t].welded;
    for (int e = 0; e < 3; ++e) {
      const uint64_t a = w[(e + 1) % 3], b = w[(e + 2) % 3];
      if (a == b) continue;
      edges[std::min(a, b) << 32 | std::max(a, b)].push_back({t, e});
    }
  }
  for (const auto& [key, sides] : edges) {
    if (sides.size() != 2) continue;
    prisms_[sides[0].first].neighbour[sides[0].second] = int(sides[1].first);
    prisms_[sides[1].first].neighbour[sides[1].second] = int(sides[0].first);
  }
}

glm::dvec3 BasePrisms::unit_normal(unsigned t, double b1, double b2) const {
  const Prism& p = prisms_[t];
  const glm::dvec3 n = p.n0 + b1 * p.m1 + b2 * p.m2;
  const double length = glm::length(n);
  return length > 0 ? n / length : p.n0;
}

glm::dvec3 BasePrisms::point(unsigned t, double b1, double b2, double s) const {
  const Prism& p = prisms_[t];
  return p.p0 + b1 * p.e1 + b2 * p.e2 - s * unit_normal(t, b1, b2);
}

glm::dvec2 BasePrisms::uv(unsigned t, double b1, double b2) const {
  const Prism& p = prisms_[t];
  return p.uv0 + b1 * p.duv1 + b2 * p.duv2;
}

void BasePrisms::frame(unsigned t, double b1, double b2, glm::dvec3& tangent,
                       glm::dvec3& bitangent) const {
  const Prism& p = prisms_[t];
  const double b0 = 1 - b1 - b2;
  uv_frame(unit_normal(t, b1, b2), b0 * p.dpdu[0] + b1 * p.dpdu[1] + b2 * p.dpdu[2],
           b0 * p.dpdv[0] + b1 * p.dpdv[1] + b2 * p.dpdv[2], tangent, bitangent);
}

bool BasePrisms::locate(const glm::dvec3& x, unsigned t, PrismPoint& out) const {
  const Prism& p = prisms_[t];
  // Unknowns (b1, b2, l) of x = p0 + b1 e1 + b2 e2 - l N(b), N unnormalised: bilinear in them,
  // so Newton's method converges in a few steps from the solution with N held at n0.
  glm::dvec3 q = p.flat_inverse * (x - p.p0);
  const double scale = glm::length(x - p.p0) + glm::length(p.e1) + glm::length(p.e2);
  for (int iteration = 0; iteration < 16; ++iteration) {
    const glm::dvec3 n = p.n0 + q.x * p.m1 + q.y * p.m2;
    const glm::dvec3 residual = p.p0 + q.x * p.e1 + q.y * p.e2 - q.z * n - x;
    const glm::dmat3 jacobian(p.e1 - q.z * p.m1, p.e2 - q.z * p.m2, -n);
    if (!(std::abs(glm::determinant(jacobian)) > 0)) return false;
    const glm::dvec3 step = glm::inverse(jacobian) * residual;
    q -= step;
    if (!std::isfinite(q.x + q.y + q.z)) return false;
    // Convergence is quadratic: after a step this small, what is left is below rounding.
    if (std::abs(step.x) + std::abs(step.y) <= 1e-9 &&
        std::abs(step.z) <= 1e-9 * (1 + std::abs(q.z)))
      break;
  }
  const glm::dvec3 n = p.n0 + q.x * p.m1 + q.y * p.m2;
  out.triangle = t;
  out.b1 = q.x;
  out.b2 = q.y;
  out.s = q.z * glm::length(n);
  return glm::length(p.p0 + q.x * p.e1 + q.y * p.e2 - q.z * n - x) <= 1e-9 * scale;
}

}  // namespace rl
