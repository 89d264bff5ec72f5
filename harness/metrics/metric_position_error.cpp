// Position error: the world distance between the technique's hit and the truth's over the
// pixels both cover, in relief depths (pos_err_*) and in texel widths at the view
// (pos_err_texels_*); artifact_pct is the share of those pixels more than one texel off.
#include "metrics/metric.h"

namespace rl {
namespace {

std::vector<double> measure_position_error(const MetricInput& in) {
  std::vector<double> depths, texels;
  long far_hits = 0;
  for (size_t i = 0; i < in.truth.size(); ++i) {
    if (!in.both_cover(i)) continue;
    const double d = in.hit_distance(i);
    depths.push_back(d / in.depth_world);
    texels.push_back(d / in.texel_world);
    far_hits += d > in.texel_world;
  }
  const ErrorStats p = error_stats(depths), t = error_stats(texels);
  const double artifact_pct = texels.empty() ? 0.0 : 100.0 * double(far_hits) / texels.size();
  return {p.mean, p.rmse, p.p99, p.max, t.mean, t.rmse, t.p99, t.max, artifact_pct};
}

const MetricRegistrar position_error(
    {.name = "position error",
     .place = 20,
     .columns = {ColumnSpec{"pos_err_mean", "depth units",
                            "mean world distance of the hit from the truth's, over jointly covered "
                            "pixels, in relief depths"}
                     .scored(),
                 ColumnSpec{"pos_err_rmse", "depth units", "root mean square of the same distance"}
                     .compared(1e-9, 0.02)
                     .reported()
                     .scored(),
                 ColumnSpec{"pos_err_p99", "depth units", "its 99th percentile"}
                     .compared(1e-9, 0.02)
                     .scored(),
                 ColumnSpec{"pos_err_max", "depth units", "its largest value"}.scored(),
                 ColumnSpec{"pos_err_texels_mean", "texels",
                            "mean distance of the hit from the truth's, in texels of the map, over "
                            "jointly covered pixels"}
                     .compared(1e-9, 0.02)
                     .reported()
                     .scored(),
                 ColumnSpec{"pos_err_texels_rmse", "texels",
                            "root mean square of the same distance"}
                     .scored(),
                 ColumnSpec{"pos_err_texels_p99", "texels", "its 99th percentile"}.scored(),
                 ColumnSpec{"pos_err_texels_max", "texels", "its largest value"}.scored(),
                 ColumnSpec{"artifact_pct", "% of covered_px",
                            "jointly covered pixels whose hit is more than one texel off (quote "
                            "coverage beside it)"}
                     .compared(0.25, 0)
                     .scored()},
     .measure = measure_position_error});

}  // namespace
}  // namespace rl
