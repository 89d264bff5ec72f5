// Coverage and the headline error. wrong_pct counts every wrong pixel of the union of covered
// pixels (technique or truth): coverage disagrees (missed or false) or both cover and the hit
// lies more than one texel from the truth's. A technique that draws empty floor, or leaves a
// silhouette out, is charged for it, unlike artifact_pct (metric_position_error.cpp).
#include <algorithm>

#include "metrics/metric.h"

namespace rl {
namespace {

std::vector<double> measure_coverage(const MetricInput& in) {
  long truth_px = 0, union_px = 0, missed = 0, false_hits = 0, far_hits = 0;
  for (size_t i = 0; i < in.truth.size(); ++i) {
    const bool tc = in.technique.covered(i), rc = in.truth.covered(i);
    truth_px += rc;
    union_px += rc || tc;
    missed += rc && !tc;
    false_hits += tc && !rc;
    far_hits += tc && rc && in.hit_distance(i) > in.texel_world;
  }
  const double covered = double(std::max(1L, truth_px));
  const double wrong =
      union_px ? 100.0 * double(missed + false_hits + far_hits) / double(union_px) : 0.0;
  return {double(truth_px), double(union_px), wrong, 100.0 * double(missed) / covered,
          100.0 * double(false_hits) / covered};
}

const MetricRegistrar coverage(
    {.name = "coverage",
     .place = 10,
     .columns = {ColumnSpec{"covered_px", "pixels", "pixels the truth covers"}.neither_better(),
                 ColumnSpec{"union_px", "pixels",
                            "pixels the technique or the truth covers: wrong_pct's denominator"}
                     .neither_better(),
                 ColumnSpec{"wrong_pct", "% of union_px",
                            "the headline error: pixels whose coverage disagrees (missed or "
                            "false) or whose hit lies more than one texel from the truth's"}
                     .compared(0.25, 0)
                     .reported()
                     .scored(),
                 ColumnSpec{"missed_pct", "% of covered_px",
                            "pixels the truth covers and the technique leaves empty"}
                     .compared(0.25, 0)
                     .reported()
                     .scored(),
                 ColumnSpec{"false_pct", "% of covered_px",
                            "pixels the technique covers and the truth leaves empty"}
                     .compared(0.25, 0)
                     .reported()
                     .scored()},
     .measure = measure_coverage});

}  // namespace
}  // namespace rl
