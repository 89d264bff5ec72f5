#pragma once
// Reference ambient occlusion at a truth hit: the visible fraction of the hemisphere above the
// base, cosine-weighted (the projected solid angle that texture-space AO approximates,
// Limberger et al., Section IV-A), estimated with occlusion rays. Directions are stratified
// over an m x m grid on the unit disk (Malley's method: uniform on the disk, lifted to the
// hemisphere, gives the cosine weighting), jittered with a generator seeded by the pixel, so
// the estimate is the same on every run and thread count.
//
// Adaptive: m starts at the most rays' side halved while it stays even and at least 6, and
// doubles until the standard error meets the target or m * m reaches the most rays. The grids
// nest: each stratum of the finer grid inside which the coarser grid's ray falls keeps that
// ray, so refining from m to 2m traces 3 m^2 new rays, not 4 m^2.
//
// The standard error accounts for the stratification: strata are paired along the azimuth and
// each pair's squared difference estimates the pair's two variances (the collapsed-strata
// estimator, Cochran, "Sampling Techniques", 1977), sqrt(sum of the pairs' squared
// differences) / m^2. It overestimates in expectation, as the pair's strata differ in mean.
// Where m is odd there is no pairing, and the binomial sqrt(p (1 - p) / m^2) stands in (an
// upper bound: stratification only lowers the variance). One ray per stratum with the error of
// independent rays, as before, overstated a 256-ray estimate's error about twice.
#include <cstdint>
#include <functional>

#include <glm/glm.hpp>

namespace rl {

struct AoSampling {
  int max_samples = 144;  // rounded to a square m * m (at least 1)
  // Stop refining once the standard error is at most this; 0: never. The stop is decided on
  // the estimate's own rays, so it biases (mostly open pixels look open on a coarse grid).
  double stderr_target = 0;
};

struct AoEstimate {
  double visibility = 1;  // unoccluded fraction, cosine-weighted
  double std_error = 0;
  int rays = 0;  // directions sampled (the finest grid's m * m)
};

// `occluded(direction)`: is the unit world direction blocked? `normal` is the base's unit
// normal at the hit, `tangent` a direction not parallel to it (made orthogonal here).
AoEstimate reference_ao(const AoSampling& sampling, uint64_t seed, const glm::dvec3& normal,
                        const glm::dvec3& tangent,
                        const std::function<bool(const glm::dvec3&)>& occluded);

}  // namespace rl
