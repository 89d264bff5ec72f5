#pragma once
// Measuring a technique's G-buffer against the truth's: every registered metric
// (metrics/metric.h, one file each: metric_*.cpp) over the same two G-buffers, so every
// technique and truth mode is measured the same way. What each column means is declared with it
// (docs/columns.md lists them). The conventions they share:
// - wrong_pct is the headline error: % of the union of covered pixels (technique or truth) that
//   are wrong, coverage disagreeing or the hit more than one texel from the truth's;
// - a column marked scored() compares with the truth: it is empty (NaN) when neither side covers
//   a pixel, never a perfect score, and unscored where the truth's own bound is too loose at the
//   view (truth_flagged);
// - position errors are world distances in relief depths (pos_err_*) or in texel widths at the
//   view (*_texels_*); shares of pixels say their denominator in their unit.
#include <string>
#include <utility>
#include <vector>

#include "core/gbuffer.h"
#include "metrics/metric.h"

namespace rl {

// A truth hit is trusted when its bound is this far below the headline's 1-texel threshold.
inline constexpr double kTruthBoundTarget = 0.05;  // texels
// A row is flagged when more than this % of its covered pixels have an untrusted truth hit.
inline constexpr double kTruthUncertainFlagPct = 0.1;

// The columns the metrics measured for one view, in row order.
class ImageMetrics {
 public:
  // Throws std::out_of_range naming a column no metric measured here.
  double at(const std::string& column) const;
  bool has(const std::string& column) const;
  // (name, value) in the column order of rows.csv; scored columns NaN when empty().
  const std::vector<std::pair<std::string, double>>& named() const& { return columns_; }
  // Of a temporary (`for (auto& c : compare_gbuffers(...).named())`), a copy that outlives it.
  std::vector<std::pair<std::string, double>> named() && { return std::move(columns_); }

  // The truth is not accurate enough at this view to score the row (metric_truth_bound.cpp).
  bool truth_flagged() const { return at("truth_uncertain_pct") > kTruthUncertainFlagPct; }
  // Nothing to measure: neither side covers a pixel.
  bool empty() const { return at("union_px") == 0; }

  void add(std::string column, double value) { columns_.emplace_back(std::move(column), value); }

 private:
  std::vector<std::pair<std::string, double>> columns_;
};

// The truth's own bound over the pixels it covers (G-buffer aux.w in texels): the largest,
// and how many exceed kTruthBoundTarget. What the row's truth columns and the run log state.
struct TruthBoundStats {
  double largest_texels = 0;
  long covered = 0, uncertain = 0;
};
TruthBoundStats truth_bound_stats(const GBuffer& truth, double texel_world);

// Does this row column compare the technique with the truth (declared scored(): an error column
// that a flagged truth makes unscoreable)? Costs, counts and the truth's own bound do not.
bool measured_against_truth(const std::string& column);

// Every metric that applies to `in`, in place order. Throws std::logic_error naming a metric
// that returns another number of values than it declares columns.
ImageMetrics measure_metrics(const MetricInput& in);

// measure_metrics of the two G-buffers; `ambient_occlusion`, `scene_shadows`: the scene asked
// for the effect, so its columns are measured.
ImageMetrics compare_gbuffers(const GBuffer& technique, const GBuffer& truth, double depth_world,
                              double texel_world, bool ambient_occlusion = false,
                              bool scene_shadows = false);

double psnr_db(const GBuffer& a, const GBuffer& b);
double ssim(const GBuffer& a, const GBuffer& b);

// The colour each pixel of an image `samples` times smaller shows when it averages the
// samples x samples pixels of `fine` under it (a box filter over the pixel's footprint, the
// background's colour included, so coverage blends at edges); alpha is the covered share. Only
// `color` is filled: the reference of psnr_footprint_db.
GBuffer footprint_color(const GBuffer& fine, int samples);

// Per-pixel position error in texels (NaN where not jointly covered), for heat maps.
std::vector<float> position_error_texels(const GBuffer& technique, const GBuffer& truth,
                                         double texel_world);

// RGB heat map, row 0 at the bottom: error 0..scale_texels through OpenCV's TURBO colour map,
// pixels the technique missed in magenta, false hits in cyan, background black.
std::vector<float> error_heat_map(const GBuffer& technique, const GBuffer& truth,
                                  double texel_world, double scale_texels);

}  // namespace rl
