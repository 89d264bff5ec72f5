#pragma once
// Reference ambient occlusion at a truth hit: the visible fraction of the hemisphere above the
// base, cosine-weighted (the projected solid angle that texture-space AO approximates,
// Limberger et al., Section IV-A), estimated with Embree occlusion rays. Directions are
// stratified over an m x m grid on the unit disk (Malley's method: uniform on the disk, lifted
// to the hemisphere, gives the cosine weighting), jittered with a generator seeded by the
// pixel, so the estimate is the same on every run and thread count.
//
// Its standard error is reported per pixel as sqrt(p (1 - p) / N), the binomial error of N
// independent rays: stratification can only lower the variance, so this is an upper bound.
#include <cstdint>
#include <functional>

#include <glm/glm.hpp>

namespace rl {

struct AoEstimate {
  double visibility = 1;  // unoccluded fraction, cosine-weighted
  double std_error = 0;
  int rays = 0;
};

// `occluded(direction)`: is the unit world direction blocked? `normal` is the base's unit
// normal at the hit, `tangent` a direction not parallel to it (made orthogonal here). `samples` is
// rounded to a square m * m (at least 1).
AoEstimate reference_ao(int samples, uint64_t seed, const glm::dvec3& normal,
                        const glm::dvec3& tangent,
                        const std::function<bool(const glm::dvec3&)>& occluded);

}  // namespace rl
