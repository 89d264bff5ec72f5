#pragma once
// Metrics comparing a technique's G-buffer with the truth's. Only ever two G-buffers: every
// technique and truth mode is measured the same way.
//
// Conventions (stated once, used everywhere):
// - wrong_pct, the headline error: % of the union of covered pixels (technique or truth)
//   that are wrong — coverage disagrees (missed or false) or both cover and the hit is more
//   than one texel from the truth's. It sees every wrong pixel: a technique that draws empty
//   floor, or leaves a silhouette out, is charged for it, unlike artifact_pct;
// - coverage: missed_pct = truth-covered pixels the technique left empty, false_pct =
//   technique-covered pixels the truth leaves empty, both in % of truth-covered pixels;
// - position error: world distance between the two hits over pixels both cover, reported in
//   units of the relief depth (pos_err_*) and of the world texel width (pos_err_texels_*);
// - artifact_pct: % of jointly covered pixels whose hit is more than one texel from the truth;
// - normal error: angle between shading normals, degrees;
// - psnr_db / ssim: shaded colour over the whole image (background black in both), PSNR
//   capped at 100 dB for identical images; SSIM after Wang et al. 2004 (11x11 Gaussian, 1.5);
// - shadow_disagree_pct: % of jointly covered pixels whose shadow flags differ;
// - object_disagree_pct: % of jointly covered pixels where one shows a plain scene object
//   (hit layer -1) and the other the relief: visibility resolved differently (depth_correct);
// - fetches_*: technique texture fetches per covered relief pixel;
// - nonfinite_px: technique pixels with a NaN or infinite output (hard cases report them);
// - the truth's own accuracy at this view, from its per-pixel bound (G-buffer aux.w, a world
//   distance along the ray: truth/truth_render.h): truth_bound_texels = the largest over the
//   pixels it covers, in texels; truth_uncertain_pct = % of the union of covered pixels where
//   the truth covers and its bound exceeds kTruthBoundTarget. A row is flagged (truth_flagged)
//   when that share exceeds kTruthUncertainFlagPct: its wrong_pct could then be the truth's
//   own error by more than that many points, so it is not to be scored;
// - with ambient_occlusion only: ao_err_mean / ao_err_p99 = |visibility - the truth's| and
//   ao_bias = mean signed difference over jointly covered relief pixels; ao_ref_stderr = the
//   truth's mean standard error there (its noise floor); ao_color_share_pct = the ambient
//   term's AO difference (ambient * albedo * |ao - ao_truth|, rgb mean) in % of the colour
//   error (rgb mean of |colour - truth's|) summed over the same pixels; color_bias = the mean
//   signed colour difference (rgb mean) there: brighter (> 0) or darker than the truth, which
//   a too open or too closed AO map shows as.
#include <string>
#include <utility>
#include <vector>

#include "core/gbuffer.h"

namespace rl {

struct ErrorStats {
  double mean = 0, rmse = 0, p99 = 0, max = 0;
};

// A truth hit is trusted when its bound is this far below the headline's 1-texel threshold.
inline constexpr double kTruthBoundTarget = 0.05;  // texels
// A row is flagged when more than this % of its covered pixels have an untrusted truth hit.
inline constexpr double kTruthUncertainFlagPct = 0.1;

// mean / rmse / 99th percentile (nearest rank) / max of the values; zeros when empty.
ErrorStats error_stats(std::vector<double> values);

struct ImageMetrics {
  long truth_covered_px = 0;
  long union_covered_px = 0;  // technique or truth covers the pixel
  double wrong_pct = 0;       // headline error (see above)
  double missed_pct = 0, false_pct = 0;
  ErrorStats pos_err;         // depth units
  ErrorStats pos_err_texels;  // texel widths
  double artifact_pct = 0;
  double normal_err_mean_deg = 0, normal_err_p99_deg = 0;
  double psnr_db = 0, ssim = 0;
  double shadow_disagree_pct = 0;
  double object_disagree_pct = 0;
  ErrorStats fetches;
  long nonfinite_px = 0;
  bool has_ao = false;  // the AO columns below are measured (and named)
  double ao_err_mean = 0, ao_err_p99 = 0, ao_bias = 0, ao_ref_stderr = 0, ao_color_share_pct = 0;
  double color_bias = 0;
  double truth_bound_texels = 0;   // largest per-pixel truth bound, texels
  double truth_uncertain_pct = 0;  // % of the union where that bound exceeds kTruthBoundTarget

  // The truth is not accurate enough at this view to score the row (see above).
  bool truth_flagged() const { return truth_uncertain_pct > kTruthUncertainFlagPct; }
  // Nothing to measure: neither side covers a pixel. Error columns are then reported empty
  // (NaN in named()), never as a perfect score.
  bool empty() const { return union_covered_px == 0; }

  // (name, value) in the column order of rows.csv; error columns NaN when empty().
  std::vector<std::pair<std::string, double>> named() const;
};

// The truth's own bound over the pixels it covers (G-buffer aux.w in texels): the largest,
// and how many exceed kTruthBoundTarget. What the row's truth columns and the run log state.
struct TruthBoundStats {
  double largest_texels = 0;
  long covered = 0, uncertain = 0;
};
TruthBoundStats truth_bound_stats(const GBuffer& truth, double texel_world);

// Does this row column compare the technique with the truth (an error column that a flagged
// truth makes unscoreable)? Costs, counts and the truth's own bound do not.
bool measured_against_truth(const std::string& column);

// `ambient_occlusion`: the scene asked for it, so the AO columns are measured.
ImageMetrics compare_gbuffers(const GBuffer& technique, const GBuffer& truth, double depth_world,
                              double texel_world, bool ambient_occlusion = false);

double psnr_db(const GBuffer& a, const GBuffer& b);
double ssim(const GBuffer& a, const GBuffer& b);

// The colour each pixel of an image `samples` times smaller shows when it averages the
// samples x samples pixels of `fine` under it (a box filter over the pixel's footprint, the
// background's colour included, so coverage blends at edges); alpha is the covered share. Only
// `color` is filled: the reference of psnr_footprint_db.
GBuffer footprint_color(const GBuffer& fine, int samples);

// psnr_footprint_db and ssim_footprint: `technique`'s colour against the footprint colour.
std::vector<std::pair<std::string, double>> footprint_metrics(const GBuffer& technique,
                                                              const GBuffer& footprint);

// Per-pixel position error in texels (NaN where not jointly covered), for heat maps.
std::vector<float> position_error_texels(const GBuffer& technique, const GBuffer& truth,
                                         double texel_world);

// RGB heat map, row 0 at the bottom: error 0..scale_texels through OpenCV's TURBO colour map,
// pixels the technique missed in magenta, false hits in cyan, background black.
std::vector<float> error_heat_map(const GBuffer& technique, const GBuffer& truth,
                                  double texel_world, double scale_texels);

}  // namespace rl
