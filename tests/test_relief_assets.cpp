// Relief assets: procedural generators, GL-identical sampling, quantisation, image loading.
#include <cmath>
#include <filesystem>
#include <map>

#include <gtest/gtest.h>

#include "core/atomic_write.h"
#include "core/error.h"
#include "relief/image_io.h"
#include "relief/procedural.h"
#include "scene/relief_asset.h"
#include "support/test_support.h"

namespace rl {
namespace {

ReliefMap make(const std::string& kind, int res, const std::map<std::string, double>& o = {}) {
  return make_procedural(kind, res, o, 10.0, "test");
}

TEST(Procedural, FlatAndConstantAreExact) {
  ReliefMap flat = make("flat", 16);
  EXPECT_EQ(flat.min_depth(), 0.0f);
  EXPECT_EQ(flat.max_depth(), 0.0f);
  ReliefMap c = make("constant", 16, {{"value", 0.25}});
  EXPECT_EQ(c.min_depth(), 0.25f);
  EXPECT_EQ(c.max_depth(), 0.25f);
  // A flat surface has the base normal.
  EXPECT_NEAR(decode_normal(glm::dvec4(c.relief[5])).z, 1.0, 1e-7);
}

TEST(Procedural, WallsAreOneTexelThick) {
  ReliefMap w = make("walls", 64, {{"spacing", 16}});
  // Row 5 is no wall row: exactly 64 / 16 wall texels (depth 0), all others at the floor.
  int walls = 0;
  for (int x = 0; x < 64; ++x) walls += w.depth_texel(x, 5) == 0.0f;
  EXPECT_EQ(walls, 4);
  for (int x = 1; x < 16; ++x) EXPECT_EQ(w.depth_texel(x, 5), 1.0f);
  EXPECT_EQ(w.depth_texel(0, 5), 0.0f);
  EXPECT_EQ(w.depth_texel(16, 5), 0.0f);
}

TEST(Procedural, BricksHaveVerticalSteps) {
  ReliefMap b = make("bricks", 128);
  EXPECT_EQ(b.min_depth(), 0.0f);
  EXPECT_FLOAT_EQ(b.max_depth(), 0.8f);
  // Somewhere two neighbouring texels differ by the full mortar depth: a vertical step.
  bool step = false;
  for (int x = 0; x < 128 && !step; ++x)
    step = std::abs(b.depth_texel(x, 0) - b.depth_texel(x, 1)) > 0.79f;
  for (int y = 0; y < 128 && !step; ++y)
    step = std::abs(b.depth_texel(0, y) - b.depth_texel(1, y)) > 0.79f;
  EXPECT_TRUE(step);
}

TEST(Procedural, PyramidsHaveSharpApexes) {
  ReliefMap p = make("pyramids", 64, {{"count", 4}});  // 16 texels per pyramid
  EXPECT_NEAR(p.min_depth(), 2.0 * 0.5 / 16, 1e-6);    // apex texels straddle the peak
  EXPECT_NEAR(p.max_depth(), 2.0 * 7.5 / 16, 1e-6);
}

TEST(Procedural, UnknownKindOrOptionIsAConfigError) {
  EXPECT_THROW(make("noise", 16), ConfigError);
  try {
    make("sines", 16, {{"frequncy", 2}});
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("frequncy"), std::string::npos);
  }
  EXPECT_THROW(make("sines", 1), ConfigError);
}

TEST(Sampling, MatchesGlLinearRepeat) {
  ReliefMap m = make("sines", 8);
  // At a texel centre the sample is the texel.
  EXPECT_NEAR(m.sample_depth(2.5 / 8, 3.5 / 8), m.depth_texel(2, 3), 1e-7);
  // Half-way between two centres it is their mean.
  EXPECT_NEAR(m.sample_depth(3.0 / 8, 3.5 / 8), 0.5 * (m.depth_texel(2, 3) + m.depth_texel(3, 3)),
              1e-7);
  // At u = 0 it wraps: the mean of the last and the first texel (GL_REPEAT).
  EXPECT_NEAR(m.sample_depth(0.0, 3.5 / 8), 0.5 * (m.depth_texel(7, 3) + m.depth_texel(0, 3)),
              1e-7);
  // Periodic in whole tiles, also far from the origin and for negative coordinates.
  EXPECT_NEAR(m.sample_depth(0.3, 0.7), m.sample_depth(-4.7, 5.7), 1e-9);
}

TEST(Sampling, AColourMapOfItsOwnSizeIsReadOnItsOwnGrid) {
  // Baboud & Decoret, Section 4.3: a 2 x 2 relief under a 4 x 4 colour map. The colour's texel
  // centres are at (i + 0.5) / 4, and it wraps on its own grid.
  ReliefMap m = make("sines", 2);
  m.color_width = m.color_height = 4;
  m.color.resize(16);
  for (int i = 0; i < 16; ++i) m.color[size_t(i)] = glm::vec4(float(i) / 16, 0, 0, 1);
  EXPECT_NEAR(m.sample_color(2.5 / 4, 1.5 / 4).r, 6.0 / 16, 1e-7);  // texel (2, 1)
  EXPECT_NEAR(m.sample_color(3.0 / 4, 1.5 / 4).r, 6.5 / 16, 1e-7);  // between (2, 1) and (3, 1)
  EXPECT_NEAR(m.sample_color(0.0, 0.5 / 4).r, 1.5 / 16, 1e-7);      // (3, 0) and (0, 0)
  // The relief keeps its own grid, and both sizes key the map.
  EXPECT_NEAR(m.sample_depth(0.25, 0.25), m.depth_texel(0, 0), 1e-7);
  ReliefMap same_bytes = m;
  same_bytes.color_width = 2;
  same_bytes.color_height = 8;
  EXPECT_NE(m.content_hash(), same_bytes.content_hash());
}

TEST(ColourResolution, TheTechniqueShadesWithTheColourMapTheTruthReads) {
  // A 32^2 brick relief under its colour at 256^2, seen from above: relief_exact finds the
  // truth's hits, so its colour matches only if the GPU reads the same 256^2 map.
  SceneDesc scene = test::procedural_scene("bricks", 32, 0.04);
  scene.color_texture_res = 256;
  const ReliefMap map = build_relief_asset(scene, 32);
  ASSERT_EQ(map.width, 32);
  ASSERT_EQ(map.color_w(), 256);
  const test::Measured m = test::measure(scene, "relief_exact", {}, View{80, 30}, 128);
  EXPECT_LT(m.metrics.at("wrong_pct"), 1.0);
  EXPECT_GT(m.metrics.at("psnr_db"), 35.0);
  // The same relief with its colour at 32^2 looks different: the test can tell the maps apart.
  SceneDesc coarse = scene;
  coarse.color_texture_res = 0;
  const test::Measured c = test::measure(coarse, "relief_exact", {}, View{80, 30}, 128);
  EXPECT_LT(psnr_db(c.technique, m.technique), m.metrics.at("psnr_db") - 3.0);
}

// truth_color_resolution: scenes that differ only in their colour map's resolution measured
// against one reference colour. Their truths' pictures are then the same bytes, where each
// scene's own colour made them differ; and the coarse colour map scores lower against the fine
// reference than against its own.
TEST(ColourResolution, ATruthColourOfItsOwnIsOneReferenceForEveryColourMap) {
  const std::string dir = test::scratch_dir("truth_colour");
  const SweepConfig config = test::run_sweep_in(R"(
[sweep]
name = "truth_colour"
views = [[80, 30]]
viewports = [64]
texture_res = [32]
frames = 1
warmup = 0
[[scene]]
name = "coarse"
relief = { procedural = "bricks", resolution = 32 }
truth_color_resolution = 256
[[scene]]
name = "fine"
relief = { procedural = "bricks", resolution = 32 }
color_resolution = 256
truth_color_resolution = 256
[[scene]]
name = "coarse_own"
relief = { procedural = "bricks", resolution = 32 }
[[technique]]
name = "relief_exact"
)",
                                                dir);
  std::map<std::string, nlohmann::json> rows = test::rows_by_scene(config, dir);
  ASSERT_EQ(rows.size(), 3u);
  auto bytes = [&](const std::string& scene) {
    return read_text(dir + "/out/" + std::string(rows[scene]["image_truth"]));
  };
  EXPECT_FALSE(bytes("fine").empty());
  EXPECT_EQ(bytes("coarse"), bytes("fine"));
  EXPECT_NE(bytes("coarse_own"), bytes("fine"));
  EXPECT_EQ(rows["coarse"]["truth"], "sampled color@256");
  EXPECT_EQ(rows["coarse_own"]["truth"], "sampled");
  // The geometry is the same: every scene's hits agree with its truth alike.
  for (const char* scene : {"coarse", "fine", "coarse_own"})
    EXPECT_LT(double(rows[scene]["wrong_pct"]), 1.0) << scene;
  EXPECT_LT(double(rows["coarse"]["psnr_db"]), double(rows["coarse_own"]["psnr_db"]) - 3.0);
  EXPECT_LT(double(rows["coarse"]["psnr_db"]), double(rows["fine"]["psnr_db"]) - 3.0);
}

TEST(Quantize, MakesEveryChannelAnExactByte) {
  ReliefMap m = make("sines", 16);
  quantize_8bit(m);
  EXPECT_TRUE(m.quantized);
  for (const auto& t : m.relief)
    for (int c = 0; c < 4; ++c) EXPECT_FLOAT_EQ(std::round(t[c] * 255.0f), t[c] * 255.0f);
}

TEST(Images, NormalMapKeepsStraightAlpha) {
  // panel1's heights sit in alpha; OIIO would premultiply colour by it unless told not to,
  // which scales the normals down. Straight values average to a unit-ish normal.
  ReliefImageSource src;
  src.normal_path = std::string(RELIEFLAB_SOURCE_DIR) + "/assets/relief/trak5/panel1_n.png";
  ReliefMap m = load_relief_images(src, 10.0);
  ASSERT_EQ(m.width, 512);
  glm::dvec4 avg(0);
  for (const auto& t : m.relief) avg += glm::dvec4(t);
  avg /= double(m.relief.size());
  EXPECT_NEAR(avg.r, 0.5, 0.02);
  EXPECT_NEAR(avg.g, 0.5, 0.02);
  EXPECT_GT(avg.b, 0.9);
  // Height convention: alpha 1 = top, so depth = 1 - alpha; panel1's alpha is at most 0.224.
  EXPECT_GT(m.min_depth(), 0.77f);
  src.normalize = true;
  ReliefMap n = load_relief_images(src, 10.0);
  EXPECT_FLOAT_EQ(n.min_depth(), 0.0f);
  EXPECT_FLOAT_EQ(n.max_depth(), 1.0f);
}

TEST(Images, FileTopRowIsVOne) {
  // write_png takes row 0 as the bottom (GL's convention); loading must give it back there.
  const std::string dir = test::scratch_dir("img");
  std::vector<float> px(4 * 4 * 3, 0.0f);
  for (int x = 0; x < 4; ++x)
    for (int c = 0; c < 3; ++c) px[(3 * 4 + x) * 3 + c] = 1.0f;  // row 3 = top
  write_png(dir + "/depth.png", 4, 4, 3, px);
  ReliefImageSource src;
  src.depth_path = dir + "/depth.png";
  src.height_convention = false;
  ReliefMap m = load_relief_images(src, 1.0);
  EXPECT_EQ(m.depth_texel(0, 3), 1.0f);  // v = 3.5 / 4, near the top of the picture
  EXPECT_EQ(m.depth_texel(0, 0), 0.0f);
}

TEST(Images, MissingFileOrAlphaIsAClearError) {
  ReliefImageSource src;
  src.normal_path = "/nonexistent/relief.png";
  try {
    load_relief_images(src, 1.0);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/relief.png"), std::string::npos);
  }
  src.normal_path = std::string(RELIEFLAB_SOURCE_DIR) + "/assets/relief/rockwall/rockwall.jpg";
  try {
    load_relief_images(src, 1.0);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("a normal map holds RGB normals and depth in alpha"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace rl

namespace rl {
namespace {

// A float map beyond [0, 1] (tests/bad_inputs/assets/depth_beyond_one.pfm: file values 0, 0.5,
// 1 and 2 per row, height convention) is refused without normalize (test_bad_inputs) and
// rescaled with it to span [0, 1] exactly, in order: it was clamped first, then normalized.
TEST(ReliefImages, NormalizeRescalesAFloatMapBeyondZeroToOne) {
  ReliefImageSource src;
  src.depth_path =
      std::string(RELIEFLAB_SOURCE_DIR) + "/tests/bad_inputs/assets/depth_beyond_one.pfm";
  src.normalize = true;
  const ReliefMap map = load_relief_images(src, 1.0);
  EXPECT_FLOAT_EQ(map.min_depth(), 0.0f);
  EXPECT_FLOAT_EQ(map.max_depth(), 1.0f);
  // Heights 0, 0.5, 1, 2 are depths 1, 0.5, 0, -1: rescaled 1, 0.75, 0.5, 0.
  EXPECT_FLOAT_EQ(map.depth_texel(0, 0), 1.0f);
  EXPECT_FLOAT_EQ(map.depth_texel(1, 0), 0.75f);
  EXPECT_FLOAT_EQ(map.depth_texel(2, 0), 0.5f);
  EXPECT_FLOAT_EQ(map.depth_texel(3, 0), 0.0f);
}

// A GeoTIFF-like terrain (heights 100 to 115 m, two texels at the nodata value -9999) with
// nodata = -9999: the valid heights span the whole depth, and the texels without data sit at
// the deepest valid depth instead of squeezing the terrain into 0.15% of it.
TEST(ReliefImages, NodataTexelsAreLeftOutOfTheRangeAndFilledAtTheDeepest) {
  ReliefImageSource src;
  src.depth_path =
      std::string(RELIEFLAB_SOURCE_DIR) + "/tests/bad_inputs/assets/terrain_nodata.tif";
  src.normalize = true;
  src.nodata = -9999;
  const ReliefMap map = load_relief_images(src, 1.0);
  EXPECT_FLOAT_EQ(map.min_depth(), 0.0f);
  EXPECT_FLOAT_EQ(map.max_depth(), 1.0f);
  // File row 0 is the top (v = 1): heights 100, 104, 108, nodata; the last row 115 is the top.
  EXPECT_FLOAT_EQ(map.depth_texel(0, 3), 1.0f);           // height 100, the lowest
  EXPECT_FLOAT_EQ(map.depth_texel(1, 3), 11.0f / 15.0f);  // height 104
  EXPECT_FLOAT_EQ(map.depth_texel(3, 3), 1.0f);           // nodata: the deepest
  EXPECT_FLOAT_EQ(map.depth_texel(0, 0), 1.0f);           // nodata
  EXPECT_FLOAT_EQ(map.depth_texel(3, 0), 0.0f);           // height 115, the top
}

// An int16 DEM (SRTM's format: heights 100 to 115 stored as integers, two texels at -32768): its
// nodata is matched as the file stores it (it reads as -1.00003 in floats), and without one,
// normalize is refused naming the stored value, not left to squeeze the terrain into a sliver.
TEST(ReliefImages, AnIntegerDemsNodataIsTheValueTheFileStores) {
  ReliefImageSource src;
  src.depth_path =
      std::string(RELIEFLAB_SOURCE_DIR) + "/tests/bad_inputs/assets/terrain_int16_nodata.tif";
  src.normalize = true;
  try {
    load_relief_images(src, 1.0);
    ADD_FAILURE() << "normalized an int16 DEM's nodata into its range";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("2 texel(s) hold -32768, the usual nodata value"),
              std::string::npos)
        << e.what();
  }
  src.nodata = -32768;
  const ReliefMap map = load_relief_images(src, 1.0);
  EXPECT_FLOAT_EQ(map.min_depth(), 0.0f);
  EXPECT_FLOAT_EQ(map.max_depth(), 1.0f);
  // File row 0 (v = 1, the map's last row): 100, 101, nodata, 102, ...; texel (2, 7) is nodata.
  EXPECT_FLOAT_EQ(map.depth_texel(2, 7), 1.0f);
  EXPECT_NEAR(map.depth_texel(0, 7), 1.0, 1e-6);  // the lowest height: the deepest
  EXPECT_LT(map.depth_texel(1, 7), map.depth_texel(0, 7));
}

}  // namespace
}  // namespace rl
