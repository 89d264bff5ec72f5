// Image similarity of the shaded colour over the whole image (background black in both):
// PSNR, capped at 100 dB for identical images, and SSIM after Wang et al. 2004 (11x11
// Gaussian window, sigma 1.5), each channel on its own, averaged.
#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "metrics/metric.h"
#include "metrics/metrics.h"

namespace rl {
namespace {

cv::Mat color_mat(const GBuffer& g) {
  cv::Mat m(g.height, g.width, CV_32FC3);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const glm::vec4& c = g.color[size_t(y) * g.width + x];
      m.at<cv::Vec3f>(y, x) =
          cv::Vec3f(stored_channel(c.r), stored_channel(c.g), stored_channel(c.b));
    }
  return m;
}

const MetricRegistrar image_similarity(
    {.name = "image similarity",
     .place = 40,
     .columns = {ColumnSpec{"psnr_db", "dB",
                            "PSNR of the shaded colour over the whole image (capped at 100)"}
                     .higher_is_better()
                     .compared(0.25, 0)
                     .reported()
                     .scored(),
                 ColumnSpec{"ssim", "",
                            "SSIM of the shaded colour over the whole image (Wang et al. 2004)"}
                     .higher_is_better()
                     .compared(0.002, 0)
                     .scored()},
     .measure = [](const MetricInput& in) -> std::vector<double> {
       return {psnr_db(in.technique, in.truth), ssim(in.technique, in.truth)};
     }});

}  // namespace

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

}  // namespace rl
