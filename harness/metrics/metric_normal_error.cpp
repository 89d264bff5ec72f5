// Normal error: the angle between the two shading normals over the pixels both cover, degrees
// (a non-finite normal counts as 180).
#include <algorithm>
#include <cmath>

#include "metrics/metric.h"

namespace rl {
namespace {

std::vector<double> measure_normal_error(const MetricInput& in) {
  std::vector<double> degrees;
  for (size_t i = 0; i < in.truth.size(); ++i) {
    if (!in.both_cover(i)) continue;
    const double cos_angle = glm::dot(glm::normalize(glm::dvec3(in.technique.normal[i])),
                                      glm::normalize(glm::dvec3(in.truth.normal[i])));
    degrees.push_back(std::isfinite(cos_angle)
                          ? glm::degrees(std::acos(std::clamp(cos_angle, -1.0, 1.0)))
                          : 180.0);
  }
  const ErrorStats s = error_stats(degrees);
  return {s.mean, s.p99};
}

const MetricRegistrar normal_error(
    {.name = "normal error",
     .place = 30,
     .columns = {ColumnSpec{"normal_err_mean_deg", "degrees",
                            "mean angle between shading normals, jointly covered"}
                     .compared(0.25, 0)
                     .reported()
                     .scored(),
                 ColumnSpec{"normal_err_p99_deg", "degrees", "its 99th percentile"}.scored()},
     .measure = measure_normal_error});

}  // namespace
}  // namespace rl
