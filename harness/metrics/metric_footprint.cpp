// Colour against the truth averaged over each pixel's footprint (a sweep's footprint_samples^2
// rays a pixel): what filtering and mip-mapping aim at, where a point-sampled truth would
// reward aliasing.
#include "metrics/metric.h"
#include "metrics/metrics.h"

namespace rl {

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

namespace {

const MetricRegistrar footprint(
    {.name = "footprint colour",
     .place = 110,
     .columns = {ColumnSpec{"psnr_footprint_db", "dB",
                            "PSNR of the shaded colour against the truth averaged over each "
                            "pixel's footprint (footprint_samples^2 rays a pixel; capped at 100): "
                            "what filtering and mip-mapping aim at"}
                     .higher_is_better()
                     .scored(),
                 ColumnSpec{"ssim_footprint", "", "SSIM against the same footprint colour"}
                     .higher_is_better()
                     .scored()},
     .applies = [](const MetricInput& in) { return in.footprint != nullptr; },
     .measure = [](const MetricInput& in) -> std::vector<double> {
       return {psnr_db(in.technique, *in.footprint), ssim(in.technique, *in.footprint)};
     }});

}  // namespace
}  // namespace rl
