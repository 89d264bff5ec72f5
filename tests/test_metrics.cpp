// Metrics on hand-made G-buffers with known answers.
#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/columns.h"
#include "metrics/metrics.h"

namespace rl {
namespace {

GBuffer filled(int w, int h) {
  GBuffer g;
  g.resize(w, h);
  for (size_t i = 0; i < g.size(); ++i) {
    g.color[i] = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
    g.position[i] = glm::vec4(0, 0, 0, 1);
    g.normal[i] = glm::vec4(0, 0, 1, 0);
    g.hit[i] = glm::vec4(0, 0, 0, 4);
  }
  return g;
}

TEST(ErrorStats, KnownValues) {
  ErrorStats s = error_stats({1, 2, 3, 4});
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(7.5));
  EXPECT_DOUBLE_EQ(s.max, 4);
  EXPECT_DOUBLE_EQ(s.p99, 4);  // nearest rank: ceil(0.99 * 4) = 4th value
  std::vector<double> hundred;
  for (int i = 1; i <= 100; ++i) hundred.push_back(i);
  EXPECT_DOUBLE_EQ(error_stats(hundred).p99, 99);
  EXPECT_DOUBLE_EQ(error_stats({}).mean, 0);
}

TEST(Metrics, IdenticalBuffersHaveNoError) {
  GBuffer a = filled(16, 16);
  ImageMetrics m = compare_gbuffers(a, a, 0.1, 0.01);
  EXPECT_EQ(m.at("covered_px"), 256);
  EXPECT_EQ(m.at("missed_pct"), 0);
  EXPECT_EQ(m.at("pos_err_max"), 0);
  EXPECT_EQ(m.at("artifact_pct"), 0);
  EXPECT_NEAR(m.at("normal_err_mean_deg"), 0, 1e-6);
  EXPECT_EQ(m.at("psnr_db"), 100);  // the stated cap for identical images
  EXPECT_NEAR(m.at("ssim"), 1.0, 1e-9);
  EXPECT_EQ(m.at("fetches_mean"), 4);
  EXPECT_EQ(m.at("nonfinite_px"), 0);
}

TEST(Metrics, CoveragePositionNormalsShadowsAndFetches) {
  GBuffer truth = filled(10, 10), tech = filled(10, 10);
  // 10 truth pixels left empty by the technique (missed); 5 empty truth pixels covered.
  for (int i = 0; i < 10; ++i) tech.color[i].a = tech.position[i].w = 0;
  for (int i = 10; i < 15; ++i) truth.color[i].a = truth.position[i].w = 0;
  // 20 jointly covered pixels off by 0.05 world units (0.5 depth units, 5 texels).
  for (int i = 20; i < 40; ++i) tech.position[i].x = 0.05f;
  // 10 pixels with normals at 90 degrees; 7 with disagreeing shadows.
  for (int i = 40; i < 50; ++i) tech.normal[i] = glm::vec4(1, 0, 0, 0);
  for (int i = 50; i < 57; ++i) tech.normal[i].w = 1;
  for (int i = 60; i < 100; ++i) tech.hit[i].w = 10;
  ImageMetrics m = compare_gbuffers(tech, truth, 0.1, 0.01);
  EXPECT_EQ(m.at("covered_px"), 95);
  EXPECT_NEAR(m.at("missed_pct"), 100.0 * 10 / 95, 1e-9);
  EXPECT_NEAR(m.at("false_pct"), 100.0 * 5 / 95, 1e-9);
  const double both = 85;
  EXPECT_NEAR(m.at("artifact_pct"), 100.0 * 20 / both, 1e-9);
  EXPECT_NEAR(m.at("pos_err_max"), 0.5, 1e-6);
  EXPECT_NEAR(m.at("pos_err_texels_max"), 5.0, 1e-5);
  EXPECT_NEAR(m.at("pos_err_mean"), 0.5 * 20 / both, 1e-6);
  EXPECT_NEAR(m.at("normal_err_mean_deg"), 90.0 * 10 / both, 1e-4);
  EXPECT_NEAR(m.at("shadow_disagree_pct"), 100.0 * 7 / both, 1e-9);
  // Fetches over the 90 technique-covered pixels: 50 x 4 and 40 x 10.
  EXPECT_NEAR(m.at("fetches_mean"), (50 * 4 + 40 * 10) / 90.0, 1e-9);
  EXPECT_EQ(m.at("fetches_max"), 10);
  // The headline error: 10 missed + 5 false + 20 off by more than a texel, over the 100
  // pixels either side covers.
  EXPECT_EQ(m.at("union_px"), 100);
  EXPECT_DOUBLE_EQ(m.at("wrong_pct"), 35.0);
}

TEST(Metrics, WrongPctCountsAFalseFloorThatArtifactPctCannotSee) {
  // A technique drawing "floor" on 60 pixels the truth leaves empty, exact elsewhere: no
  // jointly covered pixel is off, so artifact_pct is 0, while 60 of 100 covered pixels are wrong.
  GBuffer truth = filled(10, 10), tech = filled(10, 10);
  for (int i = 0; i < 60; ++i) truth.color[i].a = truth.position[i].w = 0;
  ImageMetrics m = compare_gbuffers(tech, truth, 0.1, 0.01);
  EXPECT_EQ(m.at("artifact_pct"), 0);
  EXPECT_DOUBLE_EQ(m.at("wrong_pct"), 60.0);
  EXPECT_DOUBLE_EQ(m.at("false_pct"), 150.0);  // in % of the 40 truth-covered pixels
}

TEST(Metrics, NothingCoveredIsReportedEmptyNotPerfect) {
  GBuffer truth = filled(4, 4), tech = filled(4, 4);
  for (size_t i = 0; i < truth.size(); ++i) {
    truth.color[i].a = truth.position[i].w = 0;
    tech.color[i].a = tech.position[i].w = 0;
  }
  ImageMetrics m = compare_gbuffers(tech, truth, 0.1, 0.01);
  EXPECT_TRUE(m.empty());
  for (const auto& [name, value] : m.named()) {
    // Counts, and the truth's own bound (nothing covered: nothing to be off), are zero.
    if (name == "covered_px" || name == "union_px" || name == "nonfinite_px" ||
        name.rfind("truth_", 0) == 0)
      EXPECT_EQ(value, 0) << name;
    else
      EXPECT_TRUE(std::isnan(value)) << name << " must be empty, not " << value;
  }
}

TEST(Metrics, PsnrOfAKnownDifference) {
  GBuffer a = filled(32, 32), b = filled(32, 32);
  for (auto& c : b.color) c = glm::vec4(0.6f, 0.6f, 0.6f, 1.0f);  // MSE = 0.01 -> 20 dB
  EXPECT_NEAR(psnr_db(a, b), 20.0, 1e-4);
  EXPECT_LT(ssim(a, b), 1.0);
}

TEST(Metrics, FootprintColourAveragesEverySampleUnderThePixel) {
  // A 4 x 2 fine image to 2 x 1 at 2 samples a side: each pixel the mean of its 2 x 2 block,
  // the background's colour included and alpha the covered share.
  GBuffer fine = filled(4, 2);
  const float r[8] = {0.0f, 0.2f, 1.0f, 1.0f, 0.4f, 0.6f, 1.0f, 0.0f};
  for (int i = 0; i < 8; ++i) fine.color[size_t(i)] = glm::vec4(r[i], 0.5f, 0.0f, 1.0f);
  fine.color[7] = glm::vec4(0.0f);  // uncovered: black background
  const GBuffer f = footprint_color(fine, 2);
  ASSERT_EQ(f.width, 2);
  ASSERT_EQ(f.height, 1);
  EXPECT_FLOAT_EQ(f.color[0].r, 0.3f);  // (0 + 0.2 + 0.4 + 0.6) / 4
  EXPECT_FLOAT_EQ(f.color[0].g, 0.5f);
  EXPECT_FLOAT_EQ(f.color[0].a, 1.0f);
  EXPECT_FLOAT_EQ(f.color[1].r, 0.75f);  // (1 + 1 + 1 + 0) / 4
  EXPECT_FLOAT_EQ(f.color[1].g, 0.375f);
  EXPECT_FLOAT_EQ(f.color[1].a, 0.75f);
  // Against itself at one sample a side it is the image: no error. Measured only where a
  // footprint is given.
  const GBuffer same = footprint_color(fine, 1);
  const ImageMetrics m = measure_metrics({.technique = fine, .truth = fine, .footprint = &same});
  EXPECT_EQ(m.at("psnr_footprint_db"), 100.0);
  EXPECT_NEAR(m.at("ssim_footprint"), 1.0, 1e-9);
  EXPECT_FALSE(compare_gbuffers(fine, fine, 1, 1).has("psnr_footprint_db"));
}

TEST(Metrics, NonFiniteOutputsAreCountedNotHidden) {
  GBuffer truth = filled(4, 4), tech = filled(4, 4);
  tech.position[3].x = std::numeric_limits<float>::quiet_NaN();
  tech.normal[5].y = std::numeric_limits<float>::infinity();
  ImageMetrics m = compare_gbuffers(tech, truth, 0.1, 0.01);
  EXPECT_EQ(m.at("nonfinite_px"), 2);
  EXPECT_TRUE(std::isfinite(m.at("pos_err_mean")));
  EXPECT_GT(m.at("artifact_pct"), 0);  // the NaN hit counts as an artifact, not as a perfect pixel
}

TEST(HeatMap, MarksMissedAndFalsePixels) {
  GBuffer truth = filled(2, 1), tech = filled(2, 1);
  tech.color[0].a = 0;   // missed
  truth.color[1].a = 0;  // false hit
  std::vector<float> rgb = error_heat_map(tech, truth, 0.01, 4);
  EXPECT_EQ(rgb[0], 1.0f);  // magenta
  EXPECT_EQ(rgb[1], 0.0f);
  EXPECT_EQ(rgb[2], 1.0f);
  EXPECT_EQ(rgb[3], 0.0f);  // cyan
  EXPECT_EQ(rgb[4], 1.0f);
  EXPECT_EQ(rgb[5], 1.0f);
}

TEST(Metrics, CoveredPsnrCountsOnlyTheCoveredPixels) {
  // 16 of 1024 pixels covered by both, each channel 0.1 off there: an MSE of 0.01 over the
  // covered pixels (20 dB) and 64 times less over the whole image (20 + 10 log10 64 dB).
  GBuffer truth = filled(32, 32), tech = filled(32, 32);
  for (size_t i = 0; i < truth.size(); ++i) {
    const bool covered = i < 16;
    truth.color[i] = covered ? glm::vec4(0.5f, 0.5f, 0.5f, 1.0f) : glm::vec4(0.0f);
    tech.color[i] = covered ? glm::vec4(0.6f, 0.4f, 0.6f, 1.0f) : glm::vec4(0.0f);
  }
  const ImageMetrics m = compare_gbuffers(tech, truth, 0.1, 0.01);
  EXPECT_NEAR(m.at("psnr_covered_db"), 20.0, 1e-4);
  EXPECT_NEAR(m.at("psnr_db"), 20.0 + 10.0 * std::log10(64.0), 1e-4);
  EXPECT_EQ(compare_gbuffers(truth, truth, 0.1, 0.01).at("psnr_covered_db"), 100.0);
}

// Every metric's columns, in place order, exactly as the registry declares them.
std::vector<std::string> expected_columns(const MetricInput& in) {
  std::vector<std::string> names;
  for (const Metric& metric : registered_metrics())
    if (!metric.applies || metric.applies(in))
      for (const ColumnSpec& c : metric.columns) names.push_back(c.name);
  return names;
}

TEST(MetricRegistry, MetricsWriteTheirDeclaredColumnsInPlaceOrder) {
  const GBuffer g = filled(8, 8);
  const MetricInput plain{.technique = g, .truth = g},
      ao{.technique = g, .truth = g, .ambient_occlusion = true, .footprint = &g};
  for (const MetricInput* in : {&plain, &ao}) {
    const ImageMetrics measured = measure_metrics(*in);
    std::vector<std::string> written;
    for (const auto& [name, value] : measured.named()) written.push_back(name);
    EXPECT_EQ(written, expected_columns(*in));
  }
  EXPECT_EQ(measure_metrics(plain).named().front().first, "covered_px");  // rows.csv's order
  EXPECT_FALSE(measure_metrics(plain).has("ao_err_mean"));                // AO only when asked
  double last = -1e300;
  for (const Metric& metric : registered_metrics()) {
    EXPECT_LT(last, metric.place) << metric.name;
    last = metric.place;
    for (const ColumnSpec& c : metric.columns) {
      const DeclaredColumn* declared = find_column(c.name);
      ASSERT_NE(declared, nullptr) << c.name;
      EXPECT_EQ(declared->producer, "metrics") << c.name;
      EXPECT_EQ(measured_against_truth(c.name), c.scored_against_truth) << c.name;
    }
  }
}

// A metric added in one registration: measured, declared, and empty where nothing is covered.
TEST(MetricRegistry, AnAddedMetricIsMeasuredAndDeclared) {
  register_metric({.name = "test covered share",
                   .place = 1e6,
                   .columns = {ColumnSpec{"test_covered_share_pct", "% of pixels",
                                          "pixels the truth covers, in % of the image"}
                                   .scored()},
                   .measure = [](const MetricInput& in) -> std::vector<double> {
                     double n = 0;
                     for (size_t i = 0; i < in.truth.size(); ++i) n += in.truth.covered(i);
                     return {100.0 * n / double(in.truth.size())};
                   }});
  GBuffer truth = filled(4, 4), tech = filled(4, 4);
  for (size_t i = 0; i < 12; ++i) truth.color[i].a = tech.color[i].a = 0;
  EXPECT_EQ(compare_gbuffers(tech, truth, 0.1, 0.01).at("test_covered_share_pct"), 25.0);
  EXPECT_EQ(find_column("test_covered_share_pct")->spec.unit, "% of pixels");
  for (size_t i = 0; i < truth.size(); ++i) truth.color[i].a = tech.color[i].a = 0;
  EXPECT_TRUE(std::isnan(compare_gbuffers(tech, truth, 0.1, 0.01).at("test_covered_share_pct")));
  unregister_metric("test covered share");
  EXPECT_FALSE(compare_gbuffers(tech, truth, 0.1, 0.01).has("test_covered_share_pct"));
}

TEST(MetricRegistry, RefusesAMetricThatTakesAPlaceOrMeasuresTheWrongCount) {
  const ColumnSpec column{"test_count", "pixels", "a count"};
  auto one_value = [](const MetricInput&) { return std::vector<double>{1.0}; };
  EXPECT_THROW(register_metric(
                   {.name = "test clash", .place = 10, .columns = {column}, .measure = one_value}),
               std::logic_error);  // coverage's place
  EXPECT_THROW(register_metric(
                   {.name = "coverage", .place = 2e6, .columns = {column}, .measure = one_value}),
               std::logic_error);
  EXPECT_THROW(
      register_metric({.name = "test empty", .place = 2e6, .columns = {}, .measure = one_value}),
      std::logic_error);
  register_metric({.name = "test two columns",
                   .place = 2e6,
                   .columns = {column, ColumnSpec{"test_count2", "pixels", "another count"}},
                   .measure = one_value});
  const GBuffer g = filled(2, 2);
  try {
    compare_gbuffers(g, g, 1, 1);
    ADD_FAILURE() << "a metric measuring one value for two columns was accepted";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("test two columns"), std::string::npos) << e.what();
  }
  unregister_metric("test two columns");
}

}  // namespace
}  // namespace rl
