#include "truth/reference_ao.h"

#include <cmath>
#include <vector>

#include "scene/base_mesh.h"

namespace rl {
namespace {

// SplitMix64: a small, well-mixed generator; one stream per pixel and grid from its seed.
struct SplitMix64 {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }
};

// One stratum's ray: its point on the unit square and whether the direction was open.
struct Stratum {
  double u1 = 0, u2 = 0;
  bool open = false;
};

// The first grid's side: halved from the most rays' side while it stays even and at least 6.
int first_side(int max_side) {
  int m = max_side;
  while (m / 2 >= 6 && (m / 2) % 2 == 0) m /= 2;
  return m;
}

double standard_error(const std::vector<Stratum>& grid, int m, int open) {
  const double n = double(m) * m;
  if (m % 2 == 1) {
    const double p = open / n;
    return std::sqrt(p * (1.0 - p) / n);
  }
  long differing = 0;  // pairs (i, 2k), (i, 2k + 1) whose rays disagree: squared difference 1
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; j += 2)
      differing += grid[size_t(i) * m + j].open != grid[size_t(i) * m + j + 1].open;
  return std::sqrt(double(differing)) / n;
}

}  // namespace

AoEstimate reference_ao(const AoSampling& sampling, uint64_t seed, const glm::dvec3& normal,
                        const glm::dvec3& tangent,
                        const std::function<bool(const glm::dvec3&)>& occluded) {
  const int max_side = std::max(1, int(std::lround(std::sqrt(double(sampling.max_samples)))));
  // An orthonormal frame about the normal (a base's tangent need not be orthogonal to it).
  glm::dvec3 t, bitangent;
  uv_frame(normal, tangent, glm::cross(normal, tangent), t, bitangent);
  auto trace = [&](double u1, double u2) {
    const double r = std::sqrt(u1), phi = 2.0 * M_PI * u2;
    const double z = std::sqrt(std::max(0.0, 1.0 - u1));
    const glm::dvec3 d =
        t * (r * std::cos(phi)) + bitangent * (r * std::sin(phi)) + normal * std::max(z, 1e-9);
    return !occluded(glm::normalize(d));
  };
  std::vector<Stratum> coarse, grid;
  AoEstimate e;
  for (int m = first_side(max_side); m <= max_side; m *= 2) {
    SplitMix64 rng{seed ^ (0x9e3779b97f4a7c15ull * uint64_t(m))};
    grid.assign(size_t(m) * m, Stratum{});
    int open = 0;
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) {
        Stratum& s = grid[size_t(i) * m + j];
        const Stratum* parent = coarse.empty() ? nullptr : &coarse[size_t(i / 2) * (m / 2) + j / 2];
        if (parent && int(parent->u1 * m) == i && int(parent->u2 * m) == j) {
          s = *parent;  // the coarser grid's ray lies in this stratum: keep it
        } else {
          s.u1 = (i + rng.uniform()) / m;
          s.u2 = (j + rng.uniform()) / m;
          s.open = trace(s.u1, s.u2);
        }
        open += s.open;
      }
    e.rays = m * m;
    e.visibility = double(open) / e.rays;
    e.std_error = standard_error(grid, m, open);
    if ((sampling.stderr_target > 0 && e.std_error <= sampling.stderr_target) || 2 * m > max_side)
      break;
    coarse.swap(grid);
  }
  return e;
}

}  // namespace rl
