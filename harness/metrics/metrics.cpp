#include "metrics/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/constants.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/columns.h"

namespace rl {
namespace {

// The columns ImageMetrics::named() writes (metrics.h defines each measure).
const ColumnDeclaration image_metric_columns(
    "metrics",
    {ColumnSpec{"covered_px", "pixels", "pixels the truth covers"}.neither_better(),
     ColumnSpec{"union_px", "pixels",
                "pixels the technique or the truth covers: wrong_pct's denominator"}
         .neither_better(),
     ColumnSpec{
         "wrong_pct", "% of union_px",
         "the headline error: pixels whose coverage disagrees (missed or false) or whose hit lies "
         "more than one texel from the truth's"}
         .compared(0.25, 0)
         .reported(),
     ColumnSpec{"missed_pct", "% of covered_px",
                "pixels the truth covers and the technique leaves empty"}
         .compared(0.25, 0)
         .reported(),
     ColumnSpec{"false_pct", "% of covered_px",
                "pixels the technique covers and the truth leaves empty"}
         .compared(0.25, 0)
         .reported(),
     {"pos_err_mean", "depth units",
      "mean world distance of the hit from the truth's, over "
      "jointly covered pixels, in relief depths"},
     ColumnSpec{"pos_err_rmse", "depth units", "root mean square of the same distance"}
         .compared(1e-9, 0.02)
         .reported(),
     ColumnSpec{"pos_err_p99", "depth units", "its 99th percentile"}.compared(1e-9, 0.02),
     {"pos_err_max", "depth units", "its largest value"},
     ColumnSpec{
         "pos_err_texels_mean", "texels",
         "mean distance of the hit from the truth's, in texels of the map, over jointly covered "
         "pixels"}
         .compared(1e-9, 0.02)
         .reported(),
     {"pos_err_texels_rmse", "texels", "root mean square of the same distance"},
     {"pos_err_texels_p99", "texels", "its 99th percentile"},
     {"pos_err_texels_max", "texels", "its largest value"},
     ColumnSpec{
         "artifact_pct", "% of covered_px",
         "jointly covered pixels whose hit is more than one texel off (quote coverage beside it)"}
         .compared(0.25, 0),
     ColumnSpec{"normal_err_mean_deg", "degrees",
                "mean angle between shading normals, jointly covered"}
         .compared(0.25, 0)
         .reported(),
     {"normal_err_p99_deg", "degrees", "its 99th percentile"},
     ColumnSpec{"psnr_db", "dB", "PSNR of the shaded colour over the whole image (capped at 100)"}
         .higher_is_better()
         .compared(0.25, 0)
         .reported(),
     ColumnSpec{"ssim", "", "SSIM of the shaded colour over the whole image (Wang et al. 2004)"}
         .higher_is_better()
         .compared(0.002, 0),
     ColumnSpec{"shadow_disagree_pct", "% of covered_px",
                "jointly covered pixels whose self-shadow flag differs from the truth's"}
         .compared(0.25, 0),
     ColumnSpec{
         "object_disagree_pct", "% of covered_px",
         "jointly covered pixels where one shows a plain scene object and the other the relief"}
         .compared(0.25, 0),
     ColumnSpec{"fetches_mean", "fetches", "texture fetches per covered pixel of the final image"}
         .compared(1e-9, 0.02)
         .reported(),
     {"fetches_p99", "fetches", "their 99th percentile"},
     {"fetches_max", "fetches", "their largest value"},
     {"nonfinite_px", "pixels", "pixels whose output held a NaN or an infinity"},
     ColumnSpec{
         "truth_bound_texels", "texels",
         "the largest distance the truth's hit may be off, over the pixels it covers, in texels "
         "at the view"}
         .neither_better()
         .reported(),
     ColumnSpec{"truth_uncertain_pct", "% of union_px",
                "pixels the truth covers whose truth bound exceeds 0.05 texel"}
         .neither_better()
         .reported(),
     ColumnSpec{"ao_err_mean", "visibility", "mean |AO - reference AO| over jointly covered pixels"}
         .compared(1e-9, 0.02)
         .reported(),
     {"ao_err_p99", "visibility", "its 99th percentile"},
     ColumnSpec{"ao_bias", "visibility",
                "mean (AO - reference AO): the sign says which side is darker"}
         .neither_better(),
     ColumnSpec{"ao_ref_stderr", "visibility",
                "the reference AO's own standard error, averaged: the noise floor of ao_err_mean"}
         .neither_better(),
     {"ao_color_share_pct", "% of the colour error",
      "the ambient term's AO difference as a share of the colour error, jointly covered"},
     ColumnSpec{"color_bias", "colour", "mean signed colour difference (rgb mean): > 0 brighter"}
         .neither_better()});

// The columns footprint_metrics() writes, where a sweep asks for footprint_samples.
const ColumnDeclaration footprint_columns(
    "metrics",
    {ColumnSpec{
         "psnr_footprint_db", "dB",
         "PSNR of the shaded colour against the truth averaged over each pixel's footprint "
         "(footprint_samples^2 rays a pixel; capped at 100): what filtering and mip-mapping aim at"}
         .higher_is_better(),
     ColumnSpec{"ssim_footprint", "", "SSIM against the same footprint colour"}
         .higher_is_better()});

}  // namespace

GBuffer footprint_color(const GBuffer& fine, int samples) {
  GBuffer out;
  out.width = fine.width / samples;
  out.height = fine.height / samples;
  out.color.assign(size_t(out.width) * out.height, glm::vec4(0));
  const double share = 1.0 / (double(samples) * samples);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      glm::dvec4 sum(0);
      for (int j = 0; j < samples; ++j)
        for (int i = 0; i < samples; ++i) {
          const glm::vec4 c = fine.color[size_t(y * samples + j) * fine.width + x * samples + i];
          sum += glm::dvec4(glm::dvec3(c), c.a > 0.5f ? 1.0 : 0.0);
        }
      out.color[size_t(y) * out.width + x] = glm::vec4(sum * share);
    }
  return out;
}

std::vector<std::pair<std::string, double>> footprint_metrics(const GBuffer& technique,
                                                              const GBuffer& footprint) {
  return {{"psnr_footprint_db", psnr_db(technique, footprint)},
          {"ssim_footprint", ssim(technique, footprint)}};
}

namespace {

bool finite4(const glm::vec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

cv::Mat color_mat(const GBuffer& g) {
  cv::Mat m(g.height, g.width, CV_32FC3);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const glm::vec4& c = g.color[size_t(y) * g.width + x];
      auto clamp01 = [](float v) { return std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f; };
      m.at<cv::Vec3f>(y, x) = cv::Vec3f(clamp01(c.r), clamp01(c.g), clamp01(c.b));
    }
  return m;
}

}  // namespace

ErrorStats error_stats(std::vector<double> v) {
  ErrorStats s;
  if (v.empty()) return s;
  double sum = 0, sq = 0;
  for (double e : v) {
    sum += e;
    sq += e * e;
    s.max = std::max(s.max, e);
  }
  s.mean = sum / v.size();
  s.rmse = std::sqrt(sq / v.size());
  const size_t rank = static_cast<size_t>(std::ceil(0.99 * v.size())) - 1;
  std::nth_element(v.begin(), v.begin() + rank, v.end());
  s.p99 = v[rank];
  return s;
}

double psnr_db(const GBuffer& a, const GBuffer& b) {
  cv::Mat ma = color_mat(a), mb = color_mat(b);
  cv::Mat diff;
  cv::absdiff(ma, mb, diff);
  diff = diff.mul(diff);
  const cv::Scalar s = cv::sum(diff);
  const double mse = (s[0] + s[1] + s[2]) / (3.0 * ma.total());
  if (mse <= 1e-10) return 100.0;
  return std::min(100.0, 10.0 * std::log10(1.0 / mse));
}

double ssim(const GBuffer& a, const GBuffer& b) {
  // Per channel on single-channel images (OpenCV adds a scalar to the first channel only of a
  // multi-channel matrix), then averaged.
  const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;  // (K L)^2 with L = 1
  std::vector<cv::Mat> xs, ys;
  cv::split(color_mat(a), xs);
  cv::split(color_mat(b), ys);
  auto blur = [](const cv::Mat& m) {
    cv::Mat r;
    cv::GaussianBlur(m, r, cv::Size(11, 11), 1.5);
    return r;
  };
  double total = 0;
  for (int c = 0; c < 3; ++c) {
    const cv::Mat &x = xs[c], &y = ys[c];
    cv::Mat mx = blur(x), my = blur(y);
    cv::Mat mx2 = mx.mul(mx), my2 = my.mul(my), mxy = mx.mul(my);
    cv::Mat sx2 = blur(x.mul(x)) - mx2, sy2 = blur(y.mul(y)) - my2, sxy = blur(x.mul(y)) - mxy;
    cv::Mat num = (2 * mxy + c1).mul(2 * sxy + c2);
    cv::Mat den = (mx2 + my2 + c1).mul(sx2 + sy2 + c2);
    cv::Mat map;
    cv::divide(num, den, map);
    total += cv::mean(map)[0];
  }
  return total / 3.0;
}

std::vector<float> position_error_texels(const GBuffer& t, const GBuffer& r, double texel_world) {
  std::vector<float> e(t.size(), std::numeric_limits<float>::quiet_NaN());
  for (size_t i = 0; i < t.size(); ++i)
    if (t.covered(i) && r.covered(i))
      e[i] =
          float(glm::distance(glm::dvec3(t.position[i]), glm::dvec3(r.position[i])) / texel_world);
  return e;
}

// A plain scene object's pixel (layer -1), not the relief's.
bool is_object(const GBuffer& g, size_t i) {
  return g.hit[i].z < -0.5f;
}

ImageMetrics compare_gbuffers(const GBuffer& t, const GBuffer& r, double depth_world,
                              double texel_world, bool ambient_occlusion) {
  ImageMetrics m;
  m.has_ao = ambient_occlusion;
  std::vector<double> ao_err;
  double ao_signed = 0, ao_stderr = 0, ao_color = 0, color_err = 0, color_signed = 0;
  long both = 0, missed = 0, false_hits = 0, artifacts = 0, shadow_diff = 0, object_diff = 0;
  std::vector<double> pos, pos_texels, normal_deg, fetches;
  for (size_t i = 0; i < t.size(); ++i) {
    const bool tc = t.covered(i), rc = r.covered(i);
    if (!finite4(t.color[i]) || !finite4(t.position[i]) || !finite4(t.normal[i]) ||
        !finite4(t.hit[i]))
      ++m.nonfinite_px;
    if (rc) ++m.truth_covered_px;
    if (rc || tc) ++m.union_covered_px;
    if (rc && !tc) ++missed;
    if (tc && !rc) ++false_hits;
    if (tc && !is_object(t, i)) fetches.push_back(t.hit[i].w);
    if (!(tc && rc)) continue;
    ++both;
    const double d = glm::distance(glm::dvec3(t.position[i]), glm::dvec3(r.position[i]));
    const double d_safe = std::isfinite(d) ? d : 1e30;
    pos.push_back(d_safe / depth_world);
    pos_texels.push_back(d_safe / texel_world);
    if (d_safe > texel_world) ++artifacts;
    const double cos_angle =
        glm::dot(glm::normalize(glm::dvec3(t.normal[i])), glm::normalize(glm::dvec3(r.normal[i])));
    normal_deg.push_back(std::isfinite(cos_angle)
                             ? glm::degrees(std::acos(std::clamp(cos_angle, -1.0, 1.0)))
                             : 180.0);
    if (t.shadowed(i) != r.shadowed(i)) ++shadow_diff;
    if (is_object(t, i) != is_object(r, i)) ++object_diff;
    if (ambient_occlusion && !is_object(t, i) && !is_object(r, i)) {
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
  }
  if (!ao_err.empty()) {
    const ErrorStats a = error_stats(ao_err);
    m.ao_err_mean = a.mean;
    m.ao_err_p99 = a.p99;
    m.ao_bias = ao_signed / double(ao_err.size());
    m.ao_ref_stderr = ao_stderr / double(ao_err.size());
    m.ao_color_share_pct = color_err > 0 ? std::min(100.0, 100.0 * ao_color / color_err) : 0;
    m.color_bias = color_signed / double(ao_err.size());
  }
  const double covered = std::max<long>(1, m.truth_covered_px);
  m.missed_pct = 100.0 * missed / covered;
  const TruthBoundStats bound = truth_bound_stats(r, texel_world);
  m.truth_bound_texels = bound.largest_texels;
  m.truth_uncertain_pct =
      m.union_covered_px ? 100.0 * double(bound.uncertain) / double(m.union_covered_px) : 0.0;
  m.false_pct = 100.0 * false_hits / covered;
  m.pos_err = error_stats(pos);
  m.pos_err_texels = error_stats(pos_texels);
  m.artifact_pct = both ? 100.0 * artifacts / both : 0;
  m.wrong_pct = m.union_covered_px
                    ? 100.0 * double(missed + false_hits + artifacts) / double(m.union_covered_px)
                    : 0;
  const ErrorStats n = error_stats(normal_deg);
  m.normal_err_mean_deg = n.mean;
  m.normal_err_p99_deg = n.p99;
  m.psnr_db = psnr_db(t, r);
  m.ssim = ssim(t, r);
  m.shadow_disagree_pct = both ? 100.0 * shadow_diff / both : 0;
  m.object_disagree_pct = both ? 100.0 * object_diff / both : 0;
  m.fetches = error_stats(fetches);
  return m;
}

std::vector<std::pair<std::string, double>> ImageMetrics::named() const {
  std::vector<std::pair<std::string, double>> v = {{"covered_px", double(truth_covered_px)},
                                                   {"union_px", double(union_covered_px)},
                                                   {"wrong_pct", wrong_pct},
                                                   {"missed_pct", missed_pct},
                                                   {"false_pct", false_pct},
                                                   {"pos_err_mean", pos_err.mean},
                                                   {"pos_err_rmse", pos_err.rmse},
                                                   {"pos_err_p99", pos_err.p99},
                                                   {"pos_err_max", pos_err.max},
                                                   {"pos_err_texels_mean", pos_err_texels.mean},
                                                   {"pos_err_texels_rmse", pos_err_texels.rmse},
                                                   {"pos_err_texels_p99", pos_err_texels.p99},
                                                   {"pos_err_texels_max", pos_err_texels.max},
                                                   {"artifact_pct", artifact_pct},
                                                   {"normal_err_mean_deg", normal_err_mean_deg},
                                                   {"normal_err_p99_deg", normal_err_p99_deg},
                                                   {"psnr_db", psnr_db},
                                                   {"ssim", ssim},
                                                   {"shadow_disagree_pct", shadow_disagree_pct},
                                                   {"object_disagree_pct", object_disagree_pct},
                                                   {"fetches_mean", fetches.mean},
                                                   {"fetches_p99", fetches.p99},
                                                   {"fetches_max", fetches.max},
                                                   {"nonfinite_px", double(nonfinite_px)},
                                                   {"truth_bound_texels", truth_bound_texels},
                                                   {"truth_uncertain_pct", truth_uncertain_pct}};
  if (has_ao)
    v.insert(v.end(), {{"ao_err_mean", ao_err_mean},
                       {"ao_err_p99", ao_err_p99},
                       {"ao_bias", ao_bias},
                       {"ao_ref_stderr", ao_ref_stderr},
                       {"ao_color_share_pct", ao_color_share_pct},
                       {"color_bias", color_bias}});
  if (empty())
    for (auto& [name, value] : v)
      if (name != "covered_px" && name != "union_px" && name != "nonfinite_px" &&
          name.rfind("truth_", 0) != 0)
        value = std::numeric_limits<double>::quiet_NaN();
  return v;
}

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

bool measured_against_truth(const std::string& column) {
  static const std::vector<std::string> errors = [] {
    ImageMetrics every;
    every.has_ao = true;
    std::vector<std::string> names;
    for (const auto& [name, value] : every.named())
      if (name != "covered_px" && name != "union_px" && name != "nonfinite_px" &&
          name.rfind("fetches_", 0) != 0 && name.rfind("truth_", 0) != 0)
        names.push_back(name);
    return names;
  }();
  return std::find(errors.begin(), errors.end(), column) != errors.end();
}

std::vector<float> error_heat_map(const GBuffer& t, const GBuffer& r, double texel_world,
                                  double scale_texels) {
  const std::vector<float> err = position_error_texels(t, r, texel_world);
  cv::Mat levels(1, int(t.size()), CV_8UC1);
  for (size_t i = 0; i < t.size(); ++i) {
    const double e = std::isfinite(err[i]) ? err[i] / scale_texels : 1.0;
    levels.at<uint8_t>(0, int(i)) = uint8_t(std::clamp(e, 0.0, 1.0) * 255.0 + 0.5);
  }
  cv::Mat colored;
  cv::applyColorMap(levels, colored, cv::COLORMAP_TURBO);  // BGR
  std::vector<float> rgb(t.size() * 3, 0.0f);
  for (size_t i = 0; i < t.size(); ++i) {
    const bool tc = t.covered(i), rc = r.covered(i);
    glm::vec3 c(0);
    if (tc && rc) {
      const cv::Vec3b bgr = colored.at<cv::Vec3b>(0, int(i));
      c = glm::vec3(bgr[2], bgr[1], bgr[0]) / 255.0f;
    } else if (rc) {
      c = glm::vec3(1, 0, 1);  // missed
    } else if (tc) {
      c = glm::vec3(0, 1, 1);  // false hit
    }
    rgb[3 * i] = c.r;
    rgb[3 * i + 1] = c.g;
    rgb[3 * i + 2] = c.b;
  }
  return rgb;
}

}  // namespace rl
