#include "odd_map.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "truth/heightfield_truth.h"

namespace rl {

glm::dvec3 OddMap::direction(double a, double b) {
  return {std::cos(a) * std::sin(b), std::cos(b), std::sin(a) * std::sin(b)};
}

glm::dvec3 OddMap::stored_direction(int ka, int kb) const {
  const double n = size.directions;
  return direction(M_PI * (ka + 0.5) / n, M_PI * (kb + 0.5) / n);
}

glm::dvec2 OddMap::angles(const glm::dvec3& v) {
  const double B = std::clamp(v.y, -1.0, 1.0);
  const double s = std::sqrt(std::max(0.0, 1.0 - B * B));
  const double A = s > 1e-12 ? std::clamp(v.x / s, -1.0, 1.0) : 0.0;
  return glm::dvec2(std::acos(A), std::acos(B)) / M_PI;
}

size_t OddMap::index(int x, int y, int ka, int kb) const {
  const int X = size.spatial, N = size.directions;
  const int col = direction_major ? ka * X + x : x * N + ka;
  const int row = direction_major ? kb * X + y : y * N + kb;
  return size_t(row) * width + col;
}

OddMap build_odd_map(const ReliefMap& map, OddSize size, bool direction_major,
                     glm::dvec2 depth_aspect) {
  OddMap odd;
  odd.size = size;
  odd.direction_major = direction_major;
  odd.depth_aspect = depth_aspect;
  odd.width = odd.height = size.spatial * size.directions;
  odd.texels.assign(size_t(odd.width) * odd.height, glm::vec4(0.5f, 0.5f, 1.0f, 1.0f));
  // The bilinear, tiled surface the techniques sample (its truth), at a tight tolerance.
  const HeightfieldTruth surface(map, 1e-3);
  const int X = size.spatial, N = size.directions;
  std::vector<long> missed(size_t(X) * X, 0);
  parallel_for(size_t(X) * X, [&](size_t begin, size_t end) {
    for (size_t s = begin; s < end; ++s) {
      const int x = int(s % X), y = int(s / X);
      const glm::dvec3 origin((x + 0.5) / X, (y + 0.5) / X, kOddStartDepth);
      for (int kb = 0; kb < N; ++kb)
        for (int ka = 0; ka < N; ++ka) {
          const glm::dvec3 r = odd.stored_direction(ka, kb);
          // World direction -> texture direction (u, v, depth), t counting depth units.
          const glm::dvec3 d(r.x * depth_aspect.x / r.z, r.y * depth_aspect.y / r.z, 1.0);
          const TruthHit h = surface.intersect(origin, d, 0.0, 1.0 - kOddStartDepth + 1e-6);
          glm::vec4 texel(0.5f, 0.5f, 1.0f, 1.0f);
          if (h.hit) {
            const glm::dvec4 rel = map.sample_relief(h.point.x, h.point.y);
            texel = glm::vec4(glm::vec3(rel), float(std::clamp(h.point.z, 0.0, 1.0)));
          } else {
            ++missed[s];
          }
          odd.texels[odd.index(x, y, ka, kb)] = texel;
        }
    }
  });
  for (long m : missed) odd.missed_rays += m;
  return odd;
}

}  // namespace rl
