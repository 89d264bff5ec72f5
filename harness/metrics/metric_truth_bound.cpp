// The truth's own accuracy at this view, from its per-pixel bound (G-buffer aux.w, a world
// distance along the ray: truth/truth_render.h): the largest over the pixels it covers, in
// texels, and the share of the union of covered pixels whose bound exceeds kTruthBoundTarget.
// A row where that share exceeds kTruthUncertainFlagPct is flagged, not scored
// (ImageMetrics::truth_flagged).
#include <algorithm>
#include <cmath>

#include "metrics/metric.h"
#include "metrics/metrics.h"

namespace rl {

TruthBoundStats truth_bound_stats(const GBuffer& truth, double texel_world) {
  TruthBoundStats s;
  for (size_t i = 0; i < truth.size(); ++i) {
    if (!truth.covered(i)) continue;
    const double bound = double(truth.aux[i].w) / texel_world;
    ++s.covered;
    s.largest_texels = std::max(s.largest_texels, std::isfinite(bound) ? bound : 1e30);
    s.uncertain += !(bound <= kTruthBoundTarget);
  }
  return s;
}

namespace {

std::vector<double> measure_truth_bound(const MetricInput& in) {
  const TruthBoundStats bound = truth_bound_stats(in.truth, in.texel_world);
  long union_px = 0;
  for (size_t i = 0; i < in.truth.size(); ++i) union_px += in.either_covers(i);
  return {bound.largest_texels,
          union_px ? 100.0 * double(bound.uncertain) / double(union_px) : 0.0};
}

const MetricRegistrar truth_bound(
    {.name = "truth bound",
     .place = 90,
     .columns = {ColumnSpec{"truth_bound_texels", "texels",
                            "the largest distance the truth's hit may be off, over the pixels it "
                            "covers, in texels at the view"}
                     .neither_better()
                     .reported(),
                 ColumnSpec{"truth_uncertain_pct", "% of union_px",
                            "pixels the truth covers whose truth bound exceeds 0.05 texel"}
                     .neither_better()
                     .reported()},
     .measure = measure_truth_bound});

}  // namespace
}  // namespace rl
