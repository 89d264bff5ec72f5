// PSNR of the shaded colour over the pixels the technique or the truth covers. psnr_db counts
// the whole image, so the black background around a small relief raises it: the same wrong
// pixels score higher in a wider frame. This one divides by the covered pixels only, so views
// and framings compare.
#include <algorithm>
#include <cmath>

#include "metrics/metric.h"

namespace rl {
namespace {

std::vector<double> measure_covered_psnr(const MetricInput& in) {
  double squared = 0;
  long pixels = 0;
  for (size_t i = 0; i < in.truth.size(); ++i) {
    if (!in.either_covers(i)) continue;
    ++pixels;
    for (int c = 0; c < 3; ++c) {
      const double d = double(stored_channel(in.technique.color[i][c])) -
                       double(stored_channel(in.truth.color[i][c]));
      squared += d * d;
    }
  }
  const double mse = pixels ? squared / (3.0 * double(pixels)) : 0.0;
  return {mse <= 1e-10 ? 100.0 : std::min(100.0, 10.0 * std::log10(1.0 / mse))};
}

const MetricRegistrar covered_psnr(
    {.name = "covered PSNR",
     .place = 45,
     .columns = {ColumnSpec{"psnr_covered_db", "dB",
                            "PSNR of the shaded colour over union_px only (capped at 100): unlike "
                            "psnr_db, not raised by the background around a small relief"}
                     .higher_is_better()
                     .compared(0.25, 0)
                     .scored()},
     .measure = measure_covered_psnr});

}  // namespace
}  // namespace rl
