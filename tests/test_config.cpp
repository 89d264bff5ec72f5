// Bad input gets a clear error naming the file, key or value, and writes nothing: each case
// runs the real CLI into a fresh output folder and checks the folder was never created, and
// that a folder holding earlier results is left exactly as it was.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "relief/image_io.h"
#include "support/test_support.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

const char* kGood = R"(
[sweep]
name = "ok"
elevations = [45]
viewports = [16]
frames = 1
[[scene]]
name = "flat"
relief = { procedural = "flat", resolution = 8 }
[[technique]]
name = "relief"
linear_steps = [4]
)";

std::string write_config(const std::string& dir, const std::string& text) {
  fs::create_directories(dir);
  const std::string path = dir + "/sweep.toml";
  std::ofstream(path) << text;
  return path;
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

struct BadCase {
  const char* name;
  std::string text;
  std::vector<std::string> expected;  // substrings of the message
};

// Every bad input, a test each: `test_config --gtest_filter=BadConfig.unknown_key` runs one,
// `ctest -R BadConfig` all of them.
const std::vector<BadCase>& bad_cases() {
  // Normal mapping only shades the base; the scene draws its bounding box.
  const std::string normal_on_box_scene = replace(
      replace(replace(kGood, "name = \"relief\"", "name = \"normal\""), "linear_steps = [4]", ""),
      "[[technique]]", "proxy = \"box\"\n[[technique]]");
  // Parallax cannot self-shadow; the scene asks for it.
  const std::string parallax_on_shadowed_scene = replace(
      replace(replace(kGood, "name = \"relief\"", "name = \"parallax\""), "linear_steps = [4]", ""),
      "[[technique]]", "effects = [\"self_shadow\"]\n[[technique]]");
  static const std::vector<BadCase> cases = {
      {"unknown_key",
       replace(kGood, "frames = 1", "frames = 1\nframez = 2"),
       {"sweep.toml:7", "unknown key 'framez'", "[sweep]"}},
      {"unknown_technique",
       replace(kGood, "name = \"relief\"", "name = \"releif\""),
       {"unknown technique 'releif'", "relief"}},
      {"unknown_parameter",
       replace(kGood, "linear_steps = [4]", "linear_stepz = [4]"),
       {"no parameter 'linear_stepz'"}},
      {"out_of_range",
       replace(kGood, "linear_steps = [4]", "linear_steps = [4, 0]"),
       {"linear_steps", "outside [1, 4096]"}},
      {"not_an_integer",
       replace(kGood, "linear_steps = [4]", "linear_steps = [2.5]"),
       {"linear_steps", "integer"}},
      {"bad_elevation",
       replace(kGood, "elevations = [45]", "elevations = [95]"),
       {"elevations", "[0.1, 90]"}},
      {"missing_file",
       replace(kGood, "procedural = \"flat\", resolution = 8", "normal = \"no/such/map.png\""),
       {"file not found: no/such/map.png"}},
      {"unknown_procedural",
       replace(kGood, "procedural = \"flat\"", "procedural = \"noise\""),
       {"unknown procedural relief 'noise'"}},
      {"unsupported_effect",
       parallax_on_shadowed_scene,
       {"technique 'parallax' cannot render scene 'flat': it does not support effect(s) "
        "self_shadow"}},
      {"unknown_effect",
       replace(kGood, "[[technique]]", "effects = [\"self_shadows\"]\n[[technique]]"),
       {"unknown effect 'self_shadows'"}},
      {"bad_table_value",
       std::string(kGood) + "[[table]]\nrows = [\"scene\"]\nvalues = [\"pos_err_rmes\"]\n",
       {"[[table]] value 'pos_err_rmes' is not a measured column"}},
      // Names become file and folder names: nothing may lead out of the output folder
      // (hostile input, first round), and a huge name is not echoed whole.
      {"scene_name_escapes",
       replace(kGood, "name = \"flat\"", "name = \"../../../../x\""),
       {"'name' must be a plain name", "\"../../../../x\""}},
      {"sweep_name_escapes",
       replace(kGood, "name = \"ok\"", "name = \"../../x\""),
       {"'name' must be a plain name", "\"../../x\""}},
      {"sweep_name_huge",
       replace(kGood, "name = \"ok\"", "name = \"" + std::string(100000, 'a') + "\""),
       {"'name' must be a plain name", "(100000 characters)"}},
      // Non-finite and out-of-range numbers (hostile input, first round), each named with its key.
      {"azimuth_nan",
       replace(kGood, "elevations = [45]", "elevations = [45]\nazimuths = [nan]"),
       {"'azimuths' must be a finite number, got nan"}},
      {"azimuth_inf",
       replace(kGood, "elevations = [45]", "elevations = [45]\nazimuths = [inf]"),
       {"'azimuths' must be a finite number, got inf"}},
      {"view_nan",
       replace(kGood, "elevations = [45]", "views = [[45, nan]]"),
       {"'views' must be a finite number"}},
      {"elevation_tiny",
       replace(kGood, "elevations = [45]", "elevations = [1e-9]"),
       {"elevations must be in [0.1, 90]", "got 1e-09"}},
      {"viewport_sliver",
       replace(kGood, "viewports = [16]", "viewports = [[8192, 1]]"),
       {"each viewport must be a size or [width, height] in 8..8192"}},
      {"heat_map_scale_inf",
       replace(kGood, "frames = 1", "frames = 1\nheat_map_scale = inf"),
       {"'heat_map_scale' must be a finite number"}},
      {"distance_inf",
       replace(kGood, "[[technique]]", "distance = inf\n[[technique]]"),
       {"'distance' must be a finite number, got inf"}},
      {"distance_nan",
       replace(kGood, "[[technique]]", "distance = nan\n[[technique]]"),
       {"'distance' must be a finite number, got nan"}},
      {"light_nan",
       replace(kGood, "[[technique]]", "light = [nan, 1, 1]\n[[technique]]"),
       {"'light' must be a finite number"}},
      {"shadow_bias_nan",
       replace(kGood, "[[technique]]", "shadow_bias = nan\n[[technique]]"),
       {"'shadow_bias' must be a finite number"}},
      {"shadow_intensity_nan",
       replace(kGood, "[[technique]]", "shadow_intensity = nan\n[[technique]]"),
       {"'shadow_intensity' must be a finite number"}},
      {"object_center_nan",
       replace(kGood, "[[technique]]",
               "objects = [{ shape = \"sphere\", center = [nan, 0, 0.1] }]\n[[technique]]"),
       {"'center' must be a finite number"}},
      {"ambient_out_of_range",
       replace(kGood, "[[technique]]", "ambient = [-5, 0.5, 0.5]\n[[technique]]"),
       {"each of 'ambient' must be in [0, 1], got -5"}},
      {"fov_tiny",
       replace(kGood, "[[technique]]", "fov = 1e-30\n[[technique]]"),
       {"'fov' must be in [1, 160], got 1e-30"}},
      {"size_tiny",
       replace(kGood, "[[technique]]", "size = 1e-300\n[[technique]]"),
       {"'size' must be in [0.001, 1000], got 1e-300"}},
      {"depth_huge",
       replace(kGood, "[[technique]]", "depth = 1e30\n[[technique]]"),
       {"'depth' must be in [0.0001, 10], got 1e+30"}},
      {"pyramids_count_zero",
       replace(kGood, "procedural = \"flat\", resolution = 8",
               "procedural = \"pyramids\", resolution = 8, options = { count = 0 }"),
       {"option 'count' of procedural relief 'pyramids' must be in [1, 1024], got 0"}},
      {"bricks_rows_negative",
       replace(kGood, "procedural = \"flat\", resolution = 8",
               "procedural = \"bricks\", resolution = 8, options = { rows = -3 }"),
       {"option 'rows' of procedural relief 'bricks' must be in [1, 1024], got -3"}},
      {"bricks_mortar_huge",
       replace(kGood, "procedural = \"flat\", resolution = 8",
               "procedural = \"bricks\", resolution = 8, options = { mortar = 5 }"),
       {"option 'mortar' of procedural relief 'bricks' must be in [0, 0.5], got 5"}},
      {"bad_table_aggregate",
       std::string(kGood) + "[[table]]\nvalues = [\"wrong_pct\"]\naggregate = \"median\"\n",
       {"[[table]] aggregate 'median': use \"mean\" or \"max\""}},
      {"bad_plot_axis",
       std::string(kGood) + "[[plot]]\nx = \"fetches\"\n",
       {"[[plot]] axis 'fetches'"}},
      {"box_unsupported",
       normal_on_box_scene,
       {"technique 'normal' cannot render scene 'flat': proxy = \"box\""}},
      {"truth_mesh_without_mesh",
       replace(kGood, "[[technique]]", "truth = \"mesh\"\n[[technique]]"),
       {"truth = \"mesh\" needs a mesh relief"}},
      {"mesh_with_depth",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { mesh = \"" RELIEFLAB_SOURCE_DIR
               "/assets/meshes/teapot.obj\" }\ndepth = 0.2"),
       {"'depth' comes from the mesh's proportions"}},
      {"mesh_heightfield_on_a_sphere",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { mesh = \"" RELIEFLAB_SOURCE_DIR
               "/assets/meshes/teapot.obj\" }\nbase = \"sphere\""),
       {"a baked mesh relief needs the planar base", "unless it is baked into layers"}},
      {"impostor_over_a_solid_floor",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { mesh = \"" RELIEFLAB_SOURCE_DIR
               "/assets/meshes/teapot.obj\", layers = 4 }\nfloor = \"solid\""),
       {"as an impostor has an empty floor"}},
      {"reverse_on_base",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { mesh = \"" RELIEFLAB_SOURCE_DIR
               "/assets/meshes/teapot.obj\", reverse_perspective = 2 }"),
       {"reverse_perspective needs proxy = \"box\""}},
      {"reverse_too_shallow",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { mesh = \"" RELIEFLAB_SOURCE_DIR
               "/assets/meshes/teapot.obj\", reverse_perspective = 0.5 }\nproxy = \"box\""),
       {"'reverse_perspective'", "must be > 1"}},
      {"open_gap_without_layers",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { mesh = \"" RELIEFLAB_SOURCE_DIR
               "/assets/meshes/perforated_sheet.obj\", up = \"z\", open_surface_gap = 0 }"),
       {"'open_surface_gap' applies to a mesh baked into 'layers'"}},
      {"open_gap_negative",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { mesh = \"" RELIEFLAB_SOURCE_DIR
               "/assets/meshes/perforated_sheet.obj\", layers = 4, open_surface_gap = -1 }"),
       {"'open_surface_gap' is a depth in [0, 0.5]", "got -1"}},
      {"clip_frustum_without_reverse_perspective",
       replace(kGood, "[[technique]]", "clip_frustum = true\n[[technique]]"),
       {"clip_frustum cuts a reverse-perspective frustum"}},
      {"clip_frustum_not_a_bool",
       replace(kGood, "[[technique]]", "clip_frustum = 1\n[[technique]]"),
       {"'clip_frustum' must be true"}},
      {"silhouette_unsupported",
       replace(kGood, "[[technique]]",
               "base = \"sphere\"\neffects = [\"silhouette\"]\n[[technique]]"),
       {"technique 'relief' cannot render scene 'flat': it does not support effect(s) silhouette"}},
      {"unknown_base",
       replace(kGood, "[[technique]]", "base = \"cone\"\n[[technique]]"),
       {"sweep.toml:10", "unknown base 'cone'"}},
      {"base_mesh_without_uvs",
       replace(kGood, "[[technique]]",
               "base = \"" RELIEFLAB_SOURCE_DIR "/assets/meshes/bunny.obj\"\n[[technique]]"),
       {"bunny.obj has no texture coordinates"}},
      {"curved_base_with_box",
       replace(kGood, "[[technique]]", "base = \"torus\"\nproxy = \"box\"\n[[technique]]"),
       {"a curved base is drawn itself"}},
      {"bad_object",
       replace(kGood, "[[technique]]",
               "objects = [{ shape = \"sphere\", radius = -1 }]\n[[technique]]"),
       {"'radius' must be in [0.0001, 1000], got -1"}},
      {"layers_on_a_heightfield",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { procedural = \"flat\", resolution = 8, layers = 4 }"),
       {"'layers' applies to meshes and the non-height-field patterns"}},
      {"too_many_layers",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { procedural = \"weave\", resolution = 8, layers = 9 }"),
       {"'layers'", "[1, 8]"}},
      {"weave_threads_intersect",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { procedural = \"weave\", options = { amplitude = 0.05 } }"),
       {"weave options make threads intersect"}},
      {"layers_truth_on_a_heightfield",
       replace(kGood, "[[technique]]", "truth = \"layers\"\n[[technique]]"),
       {"truth = \"layers\" needs a multilayer relief"}},
      {"floor_color_over_an_empty_floor",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { procedural = \"weave\", resolution = 8 }\n"
               "floor_color = [0.2, 0.6, 0.2]\nbase = \"sphere\""),
       {"sweep.toml:", "'floor_color' colours a layered relief's solid floor"}},
      {"floor_color_out_of_range",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { procedural = \"weave\", resolution = 8 }\nfloor = \"solid\"\n"
               "floor_color = [0.2, 1.6, 0.2]\nbase = \"sphere\""),
       {"sweep.toml:", "floor_color"}},
      {"layers_too_large",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { procedural = \"weave\", resolution = 8192, layers = 8 }"),
       {"8192x8192 texels x 8 layers exceeds"}},
      {"pattern_too_fine",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { procedural = \"weave\", options = { threads = 64, segments = 4096 } }"),
       {"triangles per tile"}},
      {"pattern_in_a_box",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { procedural = \"helix\", resolution = 8 }\nproxy = \"box\""),
       {"proxy = \"box\" is not supported yet"}},
      {"from_below_without_an_impostor",
       replace(kGood, "elevations = [45]", "elevations = [45, -30]"),
       {"scene 'flat' is seen from below", "only relief impostors"}},
      {"impostor_with_a_heightfield_technique",
       replace(kGood, "relief = { procedural = \"flat\", resolution = 8 }",
               "relief = { mesh = \"" RELIEFLAB_SOURCE_DIR
               "/assets/meshes/teapot.obj\", layers = 4, resolution = 8 }"),
       {"technique 'relief' cannot render scene 'flat': the scene is a relief impostor"}},
      {"pom_min_above_max",
       replace(kGood, "name = \"relief\"\nlinear_steps = [4]",
               "name = \"pom\"\nmin_samples = 40\nmax_samples = 20"),
       {"pom's min_samples must not exceed max_samples"}},
      {"gbuffers_not_a_bool",
       replace(kGood, "frames = 1", "frames = 1\ngbuffers = 1"),
       {"sweep.toml:7", "'gbuffers' must be true or false"}},
      {"toml_syntax",
       replace(kGood, "frames = 1", "frames = = 1"),
       {"sweep.toml:6", "TOML syntax error"}},
  };
  return cases;
}

// One bad input: the CLI exits 2 with a config error naming it, and writes nothing.
class BadConfig : public ::testing::Test {
 public:
  explicit BadConfig(const BadCase& c) : c_(c) {}
  void TestBody() override {
    const std::string dir = test::scratch_dir(c_.name);
    const std::string config = write_config(dir, c_.text);
    const std::string out = dir + "/out";
    std::string output;
    EXPECT_EQ(test::run_cli("run " + config + " --out " + out, output), 2) << output;
    EXPECT_NE(output.find("config error"), std::string::npos) << output;
    for (const auto& e : c_.expected)
      EXPECT_NE(output.find(e), std::string::npos) << "expected '" << e << "' in: " << output;
    EXPECT_FALSE(fs::exists(out)) << "a failed config wrote " << out;
  }

 private:
  const BadCase& c_;
};

// Registered by name rather than as a value-parameterised suite: CTest runs the suite as one
// test in one process (cmake/GroupedGoogleTests.cmake), and gtest names each failing input.
const bool kBadConfigsRegistered = [] {
  for (const BadCase& c : bad_cases())
    ::testing::RegisterTest("BadConfig", c.name, nullptr, nullptr, __FILE__, __LINE__,
                            [&c]() -> BadConfig* { return new BadConfig(c); });
  return true;
}();

TEST(ConfigErrors, EarlierResultsSurviveABadConfig) {
  const std::string dir = test::scratch_dir("keep");
  const std::string out = dir + "/out";
  std::string output;
  ASSERT_EQ(test::run_cli("run " + write_config(dir, kGood) + " --out " + out + " -q", output), 0)
      << output;
  const auto before = fs::last_write_time(out + "/results.sqlite");
  const auto size = fs::file_size(out + "/rows.csv");
  const std::string bad =
      write_config(dir + "/bad", replace(kGood, "linear_steps = [4]", "linear_steps = [0]"));
  EXPECT_EQ(test::run_cli("run " + bad + " --out " + out, output), 2);
  EXPECT_EQ(fs::last_write_time(out + "/results.sqlite"), before);
  EXPECT_EQ(fs::file_size(out + "/rows.csv"), size);
}

// A good first scene, then `second` (a [[scene]] block): the bad asset is in a later scene.
std::string with_second_scene(const std::string& second) {
  return replace(kGood, "[[technique]]", second + "\n[[technique]]");
}

// A PNG whose IHDR claims width x height (8-bit grey) followed by an empty IDAT and IEND:
// a reader sees the size, and there is nothing to decode.
std::string png_header_only(uint32_t width, uint32_t height) {
  auto be32 = [](uint32_t v) {
    return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  };
  auto chunk = [&](const std::string& type_and_data) {
    uint32_t crc = 0xffffffffu;  // CRC-32 of the chunk type and data, as PNG requires
    for (unsigned char c : type_and_data) {
      crc ^= c;
      for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    return be32(uint32_t(type_and_data.size() - 4)) + type_and_data + be32(~crc);
  };
  return std::string("\x89PNG\r\n\x1a\n", 8) +
         chunk("IHDR" + be32(width) + be32(height) + std::string{8, 0, 0, 0, 0}) + chunk("IDAT") +
         chunk("IEND");
}

TEST(ConfigErrors, BadAssetsInALaterSceneStopTheRunBeforeAnythingIsWritten) {
  const std::string files = test::scratch_dir("assets");
  fs::create_directories(files);
  // An image with no alpha channel to hold depth, and a truncated PNG.
  write_png(files + "/rgb.png", 8, 8, 3, std::vector<float>(8 * 8 * 3, 0.5f));
  {
    std::ifstream in(RELIEFLAB_SOURCE_DIR "/assets/relief/trak5/panel1_n.png", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(files + "/truncated.png", std::ios::binary) << bytes.substr(0, bytes.size() / 3);
  }
  // Meshes that would measure nothing: a NaN vertex, every triangle degenerate, 1e30.
  std::ofstream(files + "/nan.obj") << "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n";
  std::ofstream(files + "/inf.obj") << "v 0 0 0\nv 1 0 0\nv inf 1 0\nf 1 2 3\n";
  std::ofstream(files + "/flat.obj") << "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n";
  std::ofstream(files + "/huge.obj") << "v 0 0 0\nv 1e30 0 0\nv 0 1e30 0\nf 1 2 3\n";
  // The first hostile-input round's reports: the mesh that crashed Embree (a far vertex beside a
  // unit triangle, with uvs), a float depth map with a NaN texel, a grey + alpha PNG given as a
  // normal map, and a PNG whose header claims 100000 x 100000.
  std::ofstream(files + "/far.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1e30 1e30 1e30\n"
                                       "vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n"
                                       "f 1/1 2/2 3/3\nf 2/2 4/4 3/3\n";
  {
    std::vector<float> depth(8 * 8, 0.5f);
    depth[3 * 8 + 5] = std::nanf("");
    OIIO::ImageSpec spec(8, 8, 1, OIIO::TypeDesc::FLOAT);
    auto out = OIIO::ImageOutput::create(files + "/nan.exr");
    ASSERT_TRUE(out && out->open(files + "/nan.exr", spec));
    out->write_image(OIIO::TypeDesc::FLOAT, depth.data());
    out->close();
  }
  write_png(files + "/grey_alpha.png", 8, 8, 2, std::vector<float>(8 * 8 * 2, 0.5f));
  std::ofstream(files + "/claims_huge.png", std::ios::binary) << png_header_only(100000, 100000);
  const std::string scene = "[[scene]]\nname = \"later\"\n";
  const std::vector<BadCase> cases = {
      {"no_alpha",
       with_second_scene(scene + "relief = { normal = \"" + files + "/rgb.png\" }"),
       {"scene 'later'", "rgb.png: a normal map holds RGB normals and depth in alpha"}},
      {"truncated_png",
       with_second_scene(scene + "relief = { normal = \"" + files + "/truncated.png\" }"),
       {"scene 'later'", "truncated.png"}},
      {"nan_mesh",
       with_second_scene(scene + "relief = { mesh = \"" + files + "/nan.obj\" }\nproxy = \"box\""),
       {"nan.obj"}},  // Assimp drops the vertex: a face then refers to a missing one
      {"inf_mesh",
       with_second_scene(scene + "relief = { mesh = \"" + files + "/inf.obj\" }\nproxy = \"box\""),
       {"inf.obj", "is not a finite number"}},
      {"degenerate_mesh",
       with_second_scene(scene + "relief = { mesh = \"" + files + "/flat.obj\" }\nproxy = \"box\""),
       {"flat.obj is degenerate"}},
      {"far_vertex_mesh",
       with_second_scene(scene + "relief = { mesh = \"" + files +
                         "/far.obj\" }\nproxy = \"box\"\n" + "truth = \"mesh\""),
       {"sweep.toml:12: scene 'later'", "far.obj", "beyond 1e15"}},
      {"nan_texel",
       with_second_scene(scene + "relief = { depth = \"" + files + "/nan.exr\" }"),
       {"sweep.toml:", "scene 'later', relief", "nan.exr: texel (5, 3) channel 0 is not a finite"}},
      {"grey_alpha_normal",
       with_second_scene(scene + "relief = { normal = \"" + files + "/grey_alpha.png\" }"),
       {"grey_alpha.png: a normal map holds RGB normals and depth in alpha",
        "has 2 (grey + alpha)"}},
      {"header_claims_huge",
       with_second_scene(scene + "relief = { depth = \"" + files + "/claims_huge.png\" }"),
       {"claims_huge.png: image is 100000x100000", "at most 16384x16384"}},
      {"huge_object",
       with_second_scene(scene + "relief = { procedural = \"flat\", resolution = 8 }\n" +
                         "objects = [{ shape = \"" + files + "/huge.obj\" }]"),
       {"huge.obj", "beyond 1e15"}},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string dir = test::scratch_dir(c.name);
    const std::string out = dir + "/out";
    std::string output;
    EXPECT_EQ(test::run_cli("run " + write_config(dir, c.text) + " --out " + out, output), 2)
        << output;
    for (const auto& e : c.expected)
      EXPECT_NE(output.find(e), std::string::npos) << "expected '" << e << "' in: " << output;
    EXPECT_FALSE(fs::exists(out)) << "a bad asset wrote " << out;
  }
}

TEST(ConfigErrors, MissingConfigFile) {
  std::string output;
  EXPECT_EQ(test::run_cli("run /no/such/sweep.toml", output), 2);
  EXPECT_NE(output.find("/no/such/sweep.toml: config file not found"), std::string::npos) << output;
  // A folder given as the config (it used to say "no [[scene]] given").
  const std::string folder = test::scratch_dir("config-folder");
  fs::create_directories(folder);
  EXPECT_EQ(test::run_cli("run " + folder, output), 2);
  EXPECT_NE(output.find(folder + ": is a folder; give a sweep config file"), std::string::npos)
      << output;
}

TEST(Cli, ListAndHelp) {
  std::string output;
  ASSERT_EQ(test::run_cli("list", output), 0);
  for (const char* s :
       {"relief", "parallax", "normal", "Listing 5.3", "linear_steps", "self_shadow", "bricks"})
    EXPECT_NE(output.find(s), std::string::npos) << s;
  ASSERT_EQ(test::run_cli("--help", output), 0);
  EXPECT_NE(output.find("run"), std::string::npos);
}

}  // namespace
}  // namespace rl
