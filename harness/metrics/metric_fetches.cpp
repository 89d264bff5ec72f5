// Texture fetches per relief pixel the technique covers (its G-buffer's hit.w): evidence of
// cost, not an error, so not scored against the truth. Empty where it covers no relief pixel.
#include <limits>

#include "metrics/metric.h"

namespace rl {
namespace {

std::vector<double> measure_fetches(const MetricInput& in) {
  std::vector<double> fetches;
  for (size_t i = 0; i < in.technique.size(); ++i)
    if (in.technique.covered(i) && !shows_object(in.technique, i))
      fetches.push_back(in.technique.hit[i].w);
  if (fetches.empty()) return std::vector<double>(3, std::numeric_limits<double>::quiet_NaN());
  const ErrorStats s = error_stats(fetches);
  return {s.mean, s.p99, s.max};
}

const MetricRegistrar fetches(
    {.name = "fetches",
     .place = 70,
     .columns = {ColumnSpec{"fetches_mean", "fetches",
                            "texture fetches per covered pixel of the final image"}
                     .compared(1e-9, 0.02)
                     .reported(),
                 {"fetches_p99", "fetches", "their 99th percentile"},
                 {"fetches_max", "fetches", "their largest value"}},
     .measure = measure_fetches});

}  // namespace
}  // namespace rl
