#include "truth/reference_ao.h"

#include <cmath>

#include "scene/base_mesh.h"

namespace rl {
namespace {

// SplitMix64: a small, well-mixed generator; one stream per pixel from its seed.
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

}  // namespace

AoEstimate reference_ao(int samples, uint64_t seed, const glm::dvec3& normal,
                        const glm::dvec3& tangent,
                        const std::function<bool(const glm::dvec3&)>& occluded) {
  const int m = std::max(1, int(std::lround(std::sqrt(double(samples)))));
  // An orthonormal frame about the normal (a base's tangent need not be orthogonal to it).
  glm::dvec3 t, bitangent;
  uv_frame(normal, tangent, glm::cross(normal, tangent), t, bitangent);
  SplitMix64 rng{seed};
  int open = 0;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      const double u1 = (i + rng.uniform()) / m, u2 = (j + rng.uniform()) / m;
      const double r = std::sqrt(u1), phi = 2.0 * M_PI * u2;
      const double z = std::sqrt(std::max(0.0, 1.0 - u1));
      const glm::dvec3 d =
          t * (r * std::cos(phi)) + bitangent * (r * std::sin(phi)) + normal * std::max(z, 1e-9);
      if (!occluded(glm::normalize(d))) ++open;
    }
  AoEstimate e;
  e.rays = m * m;
  e.visibility = double(open) / e.rays;
  e.std_error = std::sqrt(e.visibility * (1.0 - e.visibility) / e.rays);
  return e;
}

}  // namespace rl
