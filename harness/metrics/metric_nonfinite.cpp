// Pixels whose output held a NaN or an infinity in any G-buffer channel: what the hard cases
// (grazing views, thin features, texture borders) are held to.
#include <cmath>

#include "metrics/metric.h"

namespace rl {
namespace {

bool finite4(const glm::vec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

std::vector<double> measure_nonfinite(const MetricInput& in) {
  const GBuffer& t = in.technique;
  long count = 0;
  for (size_t i = 0; i < t.size(); ++i)
    count += !finite4(t.color[i]) || !finite4(t.position[i]) || !finite4(t.normal[i]) ||
             !finite4(t.hit[i]);
  return {double(count)};
}

const MetricRegistrar nonfinite({.name = "non-finite output",
                                 .place = 80,
                                 .columns = {{"nonfinite_px", "pixels",
                                              "pixels whose output held a NaN or an infinity"}},
                                 .measure = measure_nonfinite});

}  // namespace
}  // namespace rl
