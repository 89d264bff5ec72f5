#include "metrics/metrics.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace rl {

double ImageMetrics::at(const std::string& column) const {
  for (const auto& [name, value] : columns_)
    if (name == column) return value;
  throw std::out_of_range("no metric measured column '" + column + "' for this view");
}

bool ImageMetrics::has(const std::string& column) const {
  return std::any_of(columns_.begin(), columns_.end(),
                     [&](const auto& named) { return named.first == column; });
}

ImageMetrics measure_metrics(const MetricInput& in) {
  bool empty = true;
  for (size_t i = 0; i < in.truth.size() && empty; ++i) empty = !in.either_covers(i);
  ImageMetrics out;
  for (const Metric& metric : registered_metrics()) {
    if (metric.applies && !metric.applies(in)) continue;
    const std::vector<double> values = metric.measure(in);
    if (values.size() != metric.columns.size())
      throw std::logic_error("metric '" + metric.name + "' measured " +
                             std::to_string(values.size()) + " values for its " +
                             std::to_string(metric.columns.size()) + " columns");
    for (size_t k = 0; k < values.size(); ++k) {
      const ColumnSpec& c = metric.columns[k];
      // A score over no pixel is no score: empty, never a perfect value.
      const bool unmeasured = empty && c.scored_against_truth;
      out.add(c.name, unmeasured ? std::numeric_limits<double>::quiet_NaN() : values[k]);
    }
  }
  return out;
}

ImageMetrics compare_gbuffers(const GBuffer& technique, const GBuffer& truth, double depth_world,
                              double texel_world, bool ambient_occlusion, bool scene_shadows) {
  return measure_metrics({.technique = technique,
                          .truth = truth,
                          .depth_world = depth_world,
                          .texel_world = texel_world,
                          .ambient_occlusion = ambient_occlusion,
                          .scene_shadows = scene_shadows});
}

bool measured_against_truth(const std::string& column) {
  const DeclaredColumn* c = find_column(column);
  return c && c->spec.scored_against_truth;
}

std::vector<float> position_error_texels(const GBuffer& t, const GBuffer& r, double texel_world) {
  std::vector<float> e(t.size(), std::numeric_limits<float>::quiet_NaN());
  for (size_t i = 0; i < t.size(); ++i)
    if (t.covered(i) && r.covered(i))
      e[i] =
          float(glm::distance(glm::dvec3(t.position[i]), glm::dvec3(r.position[i])) / texel_world);
  return e;
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
