// Raw G-buffer export (`gbuffers = true`): every cell and every truth as a multi-channel
// OpenEXR whose channels and camera header let a user re-derive what the rows report: the
// coverage counts, and each hit's pixel from its world position through the stored matrices.
#include <cmath>
#include <filesystem>
#include <set>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <glm/gtc/type_ptr.hpp>

#include "config/config.h"
#include "output/result_store.h"
#include "run/cells.h"
#include "support/test_support.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

struct Exr {
  int width = 0, height = 0;
  std::vector<std::string> names;
  std::vector<float> px;
  OIIO::ImageSpec spec;
  float at(int x, int file_row, const std::string& channel) const {
    const auto it = std::find(names.begin(), names.end(), channel);
    EXPECT_NE(it, names.end()) << channel;
    return px[(size_t(file_row) * width + x) * names.size() + size_t(it - names.begin())];
  }
  glm::mat4 matrix(const std::string& name) const {
    glm::mat4 m(0.0f);
    const OIIO::ParamValue* p = spec.find_attribute(name, OIIO::TypeMatrix);
    EXPECT_TRUE(p) << name;
    if (p) std::memcpy(glm::value_ptr(m), p->data(), sizeof m);
    return m;
  }
};

Exr read_exr(const std::string& path) {
  Exr e;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
  if (!in) return e;
  e.spec = in->spec();
  e.width = e.spec.width;
  e.height = e.spec.height;
  e.names = e.spec.channelnames;
  e.px.resize(size_t(e.width) * e.height * e.names.size());
  EXPECT_TRUE(in->read_image(0, 0, 0, -1, OIIO::TypeDesc::FLOAT, e.px.data()));
  return e;
}

TEST(GBufferExport, ChannelsAndCameraReproduceTheRow) {
  const std::string dir = test::scratch_dir("gbuffers");
  const SweepConfig config = test::run_sweep_in(R"(
[sweep]
name = "gbuffers"
elevations = [35]
azimuths = [30]
viewports = [[40, 28]]
frames = 1
warmup = 0
gbuffers = true
[[scene]]
name = "bricks"
relief = { procedural = "bricks", resolution = 32 }
[[technique]]
name = "relief"
linear_steps = [8]
)",
                                                dir);
  const std::string out = dir + "/out";
  ResultStore store(out + "/results.sqlite");
  const std::vector<Cell> cells = expand_cells(config);
  ASSERT_EQ(cells.size(), 1u);
  const Cell& cell = cells[0];
  const auto row = store.row(cell.key);
  ASSERT_TRUE(row);
  const Exr tech = read_exr(out + "/" + std::string((*row)["gbuffer"]));
  const Exr truth = read_exr(out + "/" + std::string((*row)["gbuffer_truth"]));
  const std::set<std::string> expected = {
      "R",   "G",    "B",    "A", "P.X",   "P.Y",     "P.Z",    "N.X",          "N.Y",
      "N.Z", "uv.U", "uv.V", "Z", "layer", "fetches", "shadow", "relief_depth", "truth_bound"};
  for (const Exr* e : {&tech, &truth}) {
    EXPECT_EQ(e->width, 40);
    EXPECT_EQ(e->height, 28);
    EXPECT_EQ(std::set<std::string>(e->names.begin(), e->names.end()), expected);
  }
  EXPECT_EQ(tech.spec.get_string_attribute("relieflab:technique"), "relief");
  EXPECT_EQ(tech.spec.get_string_attribute("relieflab:key"), cell.key);
  EXPECT_EQ(truth.spec.get_string_attribute("relieflab:scene"), "bricks");

  // The stored camera is the cell's camera.
  const Camera camera = make_camera(config.scenes[0], cell.view, 40, 28);
  const glm::mat4 view = truth.matrix("relieflab:view");
  const glm::mat4 world_to_screen = truth.matrix("worldToScreen");
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      EXPECT_NEAR(view[c][r], float(camera.view_matrix()[c][r]), 1e-5);
      const glm::dmat4 vp = camera.projection_matrix() * camera.view_matrix();
      EXPECT_NEAR(world_to_screen[c][r], float(vp[c][r]), 1e-4);
    }

  // Coverage counts are the row's; every covered truth hit projects back to its own pixel
  // (first file row = top), and Z is its distance along the view axis.
  long truth_covered = 0, tech_covered = 0, fetches = 0;
  for (int r = 0; r < 28; ++r)
    for (int x = 0; x < 40; ++x) {
      tech_covered += tech.at(x, r, "A") > 0.5f;
      if (tech.at(x, r, "A") > 0.5f) fetches += long(tech.at(x, r, "fetches"));
      if (truth.at(x, r, "A") < 0.5f) continue;
      ++truth_covered;
      const glm::vec4 p(truth.at(x, r, "P.X"), truth.at(x, r, "P.Y"), truth.at(x, r, "P.Z"), 1);
      const glm::vec4 clip = world_to_screen * p;
      const int gl_y = 27 - r;
      EXPECT_NEAR(clip.x / clip.w, (x + 0.5f) / 40 * 2 - 1, 1e-3) << x << "," << r;
      EXPECT_NEAR(clip.y / clip.w, (gl_y + 0.5f) / 28 * 2 - 1, 1e-3) << x << "," << r;
      EXPECT_NEAR(truth.at(x, r, "Z"), -(view * p).z, 1e-4);
      const float d = truth.at(x, r, "relief_depth");
      EXPECT_TRUE(d >= -1e-4f && d <= 1 + 1e-4f) << d;
      // The exact truth's bound: float storage of the position, under a thousandth of a texel.
      EXPECT_GT(truth.at(x, r, "truth_bound"), 0.0f);
      EXPECT_LT(truth.at(x, r, "truth_bound"), 1e-3f / 32);  // texels of 1/32
      if (tech.at(x, r, "A") > 0.5f) {
        EXPECT_EQ(tech.at(x, r, "truth_bound"), 0.0f);
      }
    }
  EXPECT_GT(truth_covered, 500);
  EXPECT_EQ(truth_covered, long((*row)["covered_px"]));
  const double missed = double((*row)["missed_pct"]) * truth_covered / 100;
  const double false_hits = double((*row)["false_pct"]) * truth_covered / 100;
  EXPECT_NEAR(double(tech_covered), truth_covered - missed + false_hits, 0.01);
  EXPECT_NEAR(double(fetches) / tech_covered, double((*row)["fetches_mean"]), 1e-6);
}

TEST(GBufferExport, OffByDefault) {
  const std::string dir = test::scratch_dir("no-gbuffers");
  test::run_sweep_in(R"(
[sweep]
name = "plain"
elevations = [45]
viewports = [16]
frames = 1
warmup = 0
[[scene]]
name = "flat"
relief = { procedural = "flat", resolution = 8 }
[[technique]]
name = "normal"
)",
                     dir);
  EXPECT_TRUE(fs::exists(dir + "/out/rows.csv"));
  EXPECT_FALSE(fs::exists(dir + "/out/gbuffers"));
}

}  // namespace
}  // namespace rl
