// A stored row is reused only when nothing it was measured from has changed (run/cell_provenance.h,
// output/provenance.h): one test per input kind changes it and checks that exactly the rows that
// depend on it are measured again, for the reason the run gives; changing nothing reuses every
// row.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/code_digest.h"
#include "core/error.h"
#include "core/precompute_cache.h"
#include "gl/shader_library.h"
#include "output/compare.h"
#include "output/result_store.h"
#include "relief/image_io.h"
#include "run/asset_check.h"
#include "run/cell_provenance.h"
#include "run/runner.h"
#include "run/shard.h"
#include "support/test_support.h"
#include "technique/technique.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

std::string read(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A 32^2 normal map with height in alpha (the common *_nm.png): bumps whose height pattern
// `variant` picks, normals tilted by them so that red, green and blue differ.
void write_normal_map(const std::string& path, int variant) {
  const int n = 32;
  std::vector<unsigned char> px(size_t(n) * n * 4);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int h = ((x / (4 + variant)) + (y / 4)) % 2 ? 230 : 40;
      unsigned char* p = &px[(size_t(y) * n + x) * 4];
      p[0] = static_cast<unsigned char>(128 + (x % 8) * 8);
      p[1] = static_cast<unsigned char>(128 - (y % 8) * 8);
      p[2] = 230;
      p[3] = static_cast<unsigned char>(h);
    }
  ImageWriteSpec spec;
  spec.width = spec.height = n;
  spec.channels = 4;
  spec.alpha_channel = 3;
  write_image_file(path, spec, px.data());
}

// Two scenes (an image relief `img`, read in `role`, and procedural bricks) and two techniques:
// four cells, so that a change to one scene or technique leaves the other two cells alone.
std::string sweep_text(const std::string& role, const std::string& sweep_extra = "") {
  return "[sweep]\nname = \"provenance\"\nelevations = [45]\nviewports = [32]\nframes = 1\n"
         "warmup = 0\n" +
         sweep_extra + "[[scene]]\nname = \"img\"\nrelief = { " + role +
         " = \"map_nm.png\" }\n"
         "[[scene]]\nname = \"bricks\"\nrelief = { procedural = \"bricks\", resolution = 32 }\n"
         "[[technique]]\nname = \"relief\"\nlinear_steps = [8]\n"
         "[[technique]]\nname = \"pom\"\n";
}

struct Fixture {
  std::string dir;
  explicit Fixture(const std::string& name) : dir(test::scratch_dir(name)) {
    fs::create_directories(dir);
    write_normal_map(dir + "/map_nm.png", 0);
  }
  SweepSummary run(const std::string& text) const {
    const SweepConfig config = parse_sweep_config(text, dir + "/sweep.toml", dir);
    RunOptions opt;
    opt.out_dir = dir + "/out";
    opt.progress = false;
    return run_sweep(config, opt);
  }
  std::string log() const { return read(dir + "/out/run.log"); }
  // The last "rows reused" line of the run log.
  std::string reuse_line() const {
    const std::string text = log();
    const size_t at = text.rfind("row(s) reused");
    if (at == std::string::npos) return "";
    const size_t start = text.rfind('\n', at) + 1;
    return text.substr(start, text.find('\n', at) - start);
  }
  // Rewrites one part of the provenance of every stored row of `technique` ("" for all), as if
  // those rows had been measured from other code.
  void tamper(const std::string& part, const std::string& technique = "") const {
    ResultStore store(dir + "/out/results.sqlite");
    for (const std::string& key : store.keys()) {
      nlohmann::ordered_json row = *store.row(key);
      if (!technique.empty() && row["technique"] != technique) continue;
      Provenance p = Provenance::parse(row["measured_from"].get<std::string>());
      for (auto& [name, digest] : p.parts)
        if (name == part) digest = "0123456789abcdef";
      row["measured_from"] = p.text();
      store.put(key, row, store.programs(key));
    }
  }
  size_t stored_rows() const { return ResultStore(dir + "/out/results.sqlite").keys().size(); }
};

TEST(Provenance, NothingChangedReusesEveryRow) {
  const Fixture f("same");
  const SweepSummary first = f.run(sweep_text("normal"));
  ASSERT_EQ(first.cells, 4u);
  const SweepSummary again = f.run(sweep_text("normal"));
  EXPECT_EQ(again.already_done, 4u);
  EXPECT_EQ(again.new_rows, 0u);
  EXPECT_EQ(again.remeasured, 0u);
  EXPECT_EQ(f.reuse_line(), "relieflab: 4 row(s) reused");
  // Every row says what it was measured from, in every part.
  ResultStore store(f.dir + "/out/results.sqlite");
  for (const std::string& key : store.keys()) {
    const Provenance p = Provenance::parse(store.row(key)->at("measured_from").get<std::string>());
    ASSERT_EQ(p.parts.size(), 8u);
    for (const auto& [name, digest] : p.parts) EXPECT_NE(digest, "unknown") << name;
    EXPECT_FALSE(parse_programs(store.programs(key)).empty());
  }
}

TEST(Provenance, AnImageRewrittenUnderItsNameReMeasuresItsScene) {
  const Fixture f("rewritten");
  f.run(sweep_text("normal"));
  write_normal_map(f.dir + "/map_nm.png", 3);
  const SweepSummary again = f.run(sweep_text("normal"));
  EXPECT_EQ(again.already_done, 2u);  // the bricks' two cells
  EXPECT_EQ(again.remeasured, 2u);
  EXPECT_EQ(f.reuse_line(),
            "relieflab: 2 row(s) reused; 2 re-measured: the inputs of scene img changed (2)");
  EXPECT_EQ(f.stored_rows(), 4u);  // the new rows replaced the old, under their new keys
}

TEST(Provenance, AFileReadInAnotherRoleReMeasuresItsScene) {
  const Fixture f("role");
  f.run(sweep_text("depth"));
  // The log names where each surface came from and warns that this one looks mis-read.
  EXPECT_NE(f.log().find("scene img reads relief depth (channel 0) from "), std::string::npos);
  EXPECT_NE(f.log().find("did you mean `normal = \"map_nm.png\"`"), std::string::npos);
  const SweepSummary again = f.run(sweep_text("normal"));
  EXPECT_EQ(again.already_done, 2u);
  EXPECT_EQ(again.remeasured, 2u);
  EXPECT_EQ(f.reuse_line(),
            "relieflab: 2 row(s) reused; 2 re-measured: the inputs of scene img changed (2)");
  EXPECT_NE(f.log().find("scene img reads relief normal (RGB normal; depth from alpha) from "),
            std::string::npos);
}

TEST(Provenance, OtherGlslReMeasuresTheTechniqueThatDrewWithIt) {
  const Fixture f("glsl");
  f.run(sweep_text("normal"));
  // The relief rows' programs as if drawn from another shader: what they list composes now to
  // other programs than the ones the rows name.
  test::store_exec(f.dir + "/out/results.sqlite",
                   "UPDATE rows SET programs = replace(programs, 'techniques/relief/relief.glsl', "
                   "'techniques/pom/pom.glsl') WHERE row LIKE '%\"technique\":\"relief\"%'");
  const SweepSummary again = f.run(sweep_text("normal"));
  EXPECT_EQ(again.already_done, 2u);
  EXPECT_EQ(again.remeasured, 2u);
  EXPECT_EQ(f.reuse_line(),
            "relieflab: 2 row(s) reused; 2 re-measured: the programs of "
            "technique relief changed (2)");
}

TEST(Provenance, APluginsFileChangedReMeasuresItsTechnique) {
  const Fixture f("plugin");
  // pom as if loaded from a shared object: its code is that file's bytes.
  const std::string plugin = f.dir + "/libpom.so";
  std::ofstream(plugin) << "first build";
  TechniqueRegistry::instance().set_plugin("pom", plugin);
  f.run(sweep_text("normal"));
  std::ofstream(plugin) << "second build, longer";
  const SweepSummary again = f.run(sweep_text("normal"));
  TechniqueRegistry::instance().set_plugin("pom", "");
  EXPECT_EQ(again.already_done, 2u);
  EXPECT_EQ(again.remeasured, 2u);
  EXPECT_EQ(f.reuse_line(),
            "relieflab: 2 row(s) reused; 2 re-measured: the code of technique pom changed (2)");
}

TEST(Provenance, TheTruthsCodeOrTheRendererChangedReMeasuresEveryRow) {
  const Fixture f("truth");
  f.run(sweep_text("normal"));
  f.tamper("truth_code");
  EXPECT_EQ(f.run(sweep_text("normal")).remeasured, 4u);
  EXPECT_EQ(f.reuse_line(),
            "relieflab: 0 row(s) reused; 4 re-measured: the truth's code changed (4)");
  f.tamper("metrics_code", "relief");
  EXPECT_EQ(f.run(sweep_text("normal")).remeasured, 2u);
  EXPECT_EQ(f.reuse_line(),
            "relieflab: 2 row(s) reused; 2 re-measured: the metrics' code changed (2)");
  f.tamper("renderer", "pom");
  EXPECT_EQ(f.run(sweep_text("normal")).remeasured, 2u);
  EXPECT_NE(f.reuse_line().find("2 re-measured: the renderer changed (the row's: "),
            std::string::npos)
      << f.reuse_line();
}

TEST(Provenance, TheCostModelChangedReMeasuresEveryRow) {
  const Fixture f("model");
  f.run(sweep_text("normal", "cost_model = \"none\"\n"));
  EXPECT_EQ(f.run(sweep_text("normal")).remeasured, 4u);
  EXPECT_EQ(f.reuse_line(),
            "relieflab: 0 row(s) reused; 4 re-measured: the cost model changed (4)");
}

TEST(Provenance, RowsStoredBeforeProvenanceAreMeasuredAgain) {
  const Fixture f("old");
  f.run(sweep_text("normal"));
  test::store_exec(f.dir + "/out/results.sqlite",
                   "UPDATE rows SET row = json_remove(row, '$.measured_from'), programs = NULL");
  EXPECT_EQ(f.run(sweep_text("normal")).remeasured, 4u);
  EXPECT_EQ(f.reuse_line(),
            "relieflab: 0 row(s) reused; 4 re-measured: it was stored before "
            "rows recorded what they were measured from (4)");
}

TEST(Provenance, StatusSaysWhatARunWouldReMeasure) {
  const Fixture f("status");
  f.run(sweep_text("normal"));
  f.tamper("programs", "pom");
  const RunStatus s = run_status({f.dir + "/out"});
  EXPECT_EQ(s.done, 2u);
  EXPECT_EQ(s.stale, 2u);
  ASSERT_EQ(s.stale_reasons.size(), 1u);
  EXPECT_EQ(s.stale_reasons[0].first, "the programs of technique pom changed");
  EXPECT_NE(format_run_status(s).find("2 stored row(s) were measured from other code or inputs"),
            std::string::npos);
}

TEST(Provenance, CompareSaysWhichPartsOfMatchedRowsDiffer) {
  const Fixture f("compare");
  f.run(sweep_text("normal"));
  fs::copy(f.dir + "/out", f.dir + "/base", fs::copy_options::recursive);
  f.tamper("programs", "relief");
  f.run(sweep_text("normal"));
  const Comparison c = compare_runs(f.dir + "/base", f.dir + "/out", default_tolerances());
  EXPECT_EQ(c.matched_by_key, 4u);
  EXPECT_TRUE(c.measured_from_differs.empty());  // re-measured by this build: the same again
  // A base run measured by another build of relief: its rows pair up by key, and the report
  // says they came from other programs.
  {
    ResultStore store(f.dir + "/base/results.sqlite");
    for (const std::string& key : store.keys()) {
      nlohmann::ordered_json row = *store.row(key);
      if (row["technique"] != "relief") continue;
      Provenance p = Provenance::parse(row["measured_from"].get<std::string>());
      for (auto& [name, digest] : p.parts)
        if (name == "programs") digest = "0123456789abcdef";
      row["measured_from"] = p.text();
      row["wrong_pct"] = row["wrong_pct"].get<double>() + 50;  // and it measured better
      store.put(key, row, store.programs(key));
    }
  }
  const Comparison d = compare_runs(f.dir + "/base", f.dir + "/out", default_tolerances());
  ASSERT_EQ(d.measured_from_differs.size(), 1u);
  EXPECT_EQ(d.measured_from_differs.begin()->first, "programs");
  EXPECT_EQ(d.measured_from_differs.begin()->second, 2u);
  const std::string report = format_comparison(d);
  EXPECT_NE(report.find("2 matched cell(s) were measured from other code or inputs"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("linear_steps=8"), std::string::npos) << report;  // the setting, named
  EXPECT_NE(report.find("(measured from other programs)"), std::string::npos) << report;
}

TEST(Provenance, CompareNamesTheSettingOfATechniqueItDoesNotKnow) {
  // A plugin's rows compared without --plugins: the row's own `setting` names its parameters.
  const nlohmann::ordered_json base = {{"technique", "engine_pom"},
                                       {"scene", "rock"},
                                       {"elevation_deg", 20.0},
                                       {"azimuth_deg", 30.0},
                                       {"viewport", "512x512"},
                                       {"texture_size", "1024x1024"},
                                       {"setting", "layers_max=32 layers_min=8"},
                                       {"wrong_pct", 3.2}};
  nlohmann::ordered_json now = base;
  now["wrong_pct"] = 8.2;
  const Comparison c = compare_rows({{"k", base}}, {{"k", now}}, default_tolerances());
  ASSERT_EQ(c.worse.size(), 1u);
  EXPECT_EQ(c.worse[0].cell, "rock el 20 az 30 512x512 tex 1024x1024 layers_max=32 layers_min=8");
}

TEST(Provenance, AReplacedRowIsReplacedInOneTransaction) {
  const std::string dir = test::scratch_dir("store");
  fs::create_directories(dir);
  ResultStore store(dir + "/results.sqlite");
  store.put("old", {{"v", 1}}, "[]");
  store.put("new", {{"v", 2}}, "[]", "old");
  EXPECT_EQ(store.keys(), (std::set<std::string>{"new"}));
  EXPECT_EQ(store.row("new")->at("v"), 2);
  store.put("new", {{"v", 3}});  // replaced in place, without programs
  EXPECT_EQ(store.row("new")->at("v"), 3);
  EXPECT_EQ(store.programs("new"), "");
}

TEST(Provenance, ProgramDigestsFollowTheComposedSource) {
  const ProgramDesc relief{"relief",
                           "harness/glsl/base.vert",
                           {"techniques/relief/relief.glsl", "harness/glsl/surface_main.glsl"},
                           {{"RL_LINEAR_STEPS", "8"}},
                           ""};
  ProgramDesc other = relief;
  other.fragment_files[0] = "techniques/pom/pom.glsl";
  ProgramDesc more_steps = relief;
  more_steps.defines["RL_LINEAR_STEPS"] = "16";
  EXPECT_EQ(program_digest(relief), program_digest(relief));
  EXPECT_NE(program_digest(relief), program_digest(other));
  EXPECT_NE(program_digest(relief), program_digest(more_steps));
  // A list's digest is its programs', in any order; a file gone makes it unknown ("").
  EXPECT_EQ(programs_digest({relief, other}), programs_digest({other, relief}));
  ProgramDesc gone = relief;
  gone.fragment_files[0] = "techniques/relief/no_such_file.glsl";
  EXPECT_EQ(programs_digest({relief, gone}), "");
  const std::map<std::string, ProgramDesc> uses = {{"a", relief}, {"b", more_steps}};
  EXPECT_EQ(programs_digest(parse_programs(programs_text(uses))),
            programs_digest({relief, more_steps}));
  EXPECT_TRUE(parse_programs("not json").empty());
}

TEST(Provenance, CodeDigestsNameTheBuildsFolders) {
  EXPECT_EQ(source_folder(std::string(RELIEFLAB_SOURCE_DIR) + "/techniques/relief/relief.cpp"),
            "techniques/relief");
  EXPECT_EQ(folder_digest("techniques/relief").size(), 16u);
  EXPECT_NE(folder_digest("techniques/relief"), folder_digest("techniques/pom"));
  EXPECT_EQ(folder_digest("/elsewhere/my_plugin"), "");
  register_folder_digest("/elsewhere/my_plugin", "00000000deadbeef");
  EXPECT_EQ(folder_digest("/elsewhere/my_plugin"), "00000000deadbeef");
  EXPECT_THROW(code_digest({"harness/no_such_layer"}), std::logic_error);
  EXPECT_NE(code_digest({"harness/truth"}), code_digest({"harness/metrics"}));
}

TEST(Provenance, APrecomputeIsReadBackOnlyByTheCodeThatMadeIt) {
  const std::string dir = test::scratch_dir("cache");
  const char* before = std::getenv("RELIEFLAB_CACHE_DIR");
  const std::string kept = before ? before : "";
  setenv("RELIEFLAB_CACHE_DIR", dir.c_str(), 1);
  const std::vector<uint32_t> made = {1, 2, 3, 4};
  write_precompute_cache("provenance_test", "method 1", 42, made.data(), 16);
  std::vector<uint32_t> read(4);
  EXPECT_TRUE(read_precompute_cache("provenance_test", "method 1", 42, read.data(), 16));
  EXPECT_EQ(read, made);
  // The same options and map from code in another folder: another precompute, not this one.
  EXPECT_FALSE(
      test::read_precompute_cache_elsewhere("provenance_test", "method 1", 42, read.data(), 16));
  if (before)
    setenv("RELIEFLAB_CACHE_DIR", kept.c_str(), 1);
  else
    unsetenv("RELIEFLAB_CACHE_DIR");
}

TEST(Provenance, EachFileIsReadOnceForItsDigest) {
  const std::string dir = test::scratch_dir("digest");
  fs::create_directories(dir);
  write_normal_map(dir + "/a.png", 0);
  const uint64_t before = file_digest_reads();
  const std::string d = file_digest(dir + "/a.png");
  EXPECT_EQ(file_digest(dir + "/a.png"), d);
  EXPECT_EQ(file_digest_reads(), before + 1);
  write_normal_map(dir + "/a.png", 2);  // rewritten: another size or time, read again
  fs::last_write_time(dir + "/a.png",
                      fs::last_write_time(dir + "/a.png") + std::chrono::seconds(2));
  EXPECT_NE(file_digest(dir + "/a.png"), d);
  EXPECT_EQ(file_digest_reads(), before + 2);
  EXPECT_EQ(file_digest(dir + "/missing.png"), "");
}

TEST(Provenance, ADepthFileWithHeightInAlphaIsNamedWithTheFix) {
  const std::string dir = test::scratch_dir("alpha");
  fs::create_directories(dir);
  write_normal_map(dir + "/map_nm.png", 0);
  EXPECT_NE(depth_file_alpha_problem(dir + "/map_nm.png").find("did you mean `normal = "),
            std::string::npos);
  // A grey depth map, with or without an alpha channel of its own, is what it says.
  std::vector<unsigned char> grey(16 * 16 * 4, 200);
  ImageWriteSpec spec;
  spec.width = spec.height = 16;
  spec.channels = 4;
  spec.alpha_channel = 3;
  for (size_t i = 0; i < grey.size(); i += 4) grey[i + 3] = static_cast<unsigned char>(i % 251);
  write_image_file(dir + "/grey.png", spec, grey.data());
  EXPECT_EQ(depth_file_alpha_problem(dir + "/grey.png"), "");
}

}  // namespace
}  // namespace rl
