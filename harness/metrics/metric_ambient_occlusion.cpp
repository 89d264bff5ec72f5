// Ambient occlusion, where the scene asks for it, over the relief pixels both cover (G-buffer
// aux: x the visibility shaded with, y its standard error, z the unoccluded ambient term):
// ao_err_mean / ao_err_p99 = |visibility - the truth's|, ao_bias the mean signed difference,
// ao_ref_stderr the truth's mean standard error there (its noise floor), ao_color_share_pct
// the ambient term's AO difference (ambient * albedo * |ao - ao_truth|) in % of the colour
// error (rgb mean of |colour - truth's|), and color_bias the mean signed colour difference:
// brighter (> 0) or darker than the truth, which a too open or too closed AO map shows as.
#include <algorithm>
#include <cmath>

#include "metrics/metric.h"

namespace rl {
namespace {

std::vector<double> measure_ambient_occlusion(const MetricInput& in) {
  const GBuffer &t = in.technique, &r = in.truth;
  std::vector<double> ao_err;
  double ao_signed = 0, ao_stderr = 0, ao_color = 0, color_err = 0, color_signed = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    if (!in.both_cover(i) || shows_object(t, i) || shows_object(r, i)) continue;
    const double diff = double(t.aux[i].x) - double(r.aux[i].x);
    ao_err.push_back(std::abs(diff));
    ao_signed += diff;
    ao_stderr += r.aux[i].y;
    ao_color += double(t.aux[i].z) * std::abs(diff);
    for (int c = 0; c < 3; ++c) {
      const double dc = double(t.color[i][c]) - r.color[i][c];
      color_err += std::abs(dc) / 3;
      color_signed += dc / 3;
    }
  }
  if (ao_err.empty()) return std::vector<double>(6, 0.0);
  const ErrorStats a = error_stats(ao_err);
  const double n = double(ao_err.size());
  return {a.mean,
          a.p99,
          ao_signed / n,
          ao_stderr / n,
          color_err > 0 ? std::min(100.0, 100.0 * ao_color / color_err) : 0.0,
          color_signed / n};
}

const MetricRegistrar ambient_occlusion(
    {.name = "ambient occlusion",
     .place = 100,
     .columns = {ColumnSpec{"ao_err_mean", "visibility",
                            "mean |AO - reference AO| over jointly covered pixels"}
                     .compared(1e-9, 0.02)
                     .reported()
                     .scored(),
                 ColumnSpec{"ao_err_p99", "visibility", "its 99th percentile"}.scored(),
                 ColumnSpec{"ao_bias", "visibility",
                            "mean (AO - reference AO): the sign says which side is darker"}
                     .neither_better()
                     .scored(),
                 ColumnSpec{"ao_ref_stderr", "visibility",
                            "the reference AO's own standard error, averaged: the noise floor of "
                            "ao_err_mean"}
                     .neither_better()
                     .scored(),
                 ColumnSpec{
                     "ao_color_share_pct", "% of the colour error",
                     "the ambient term's AO difference as a share of the colour error, jointly "
                     "covered"}
                     .scored(),
                 ColumnSpec{"color_bias", "colour",
                            "mean signed colour difference (rgb mean): > 0 brighter"}
                     .neither_better()
                     .scored()},
     .applies = [](const MetricInput& in) { return in.ambient_occlusion; },
     .measure = measure_ambient_occlusion});

}  // namespace
}  // namespace rl
