// The plugin interface: registration refuses what would silently break a sweep (a taken name,
// inconsistent metadata, a parameter name meaning two things), and a plugin's cross-parameter
// check runs for every setting of a config before anything is written. Paired settings
// (`sets`) combine with the parameter lists as documented.
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "config/config.h"
#include "config/config_technique.h"
#include "core/atomic_write.h"
#include "core/error.h"
#include "core/params.h"
#include "run/cells.h"
#include "support/test_support.h"
#include "technique/contract.h"
#include "technique/technique.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

// A throwaway plugin with a cross-parameter rule, as a POM-like technique would have.
class PairedSamples : public Technique {
 public:
  using Technique::Technique;
  static TechniqueInfo describe() {
    return {.name = "test_paired_samples",
            .title = "Test plugin: paired sample counts",
            .citation = "tests/test_registry.cpp",
            .effects = {},
            .params = {{.name = "min_samples",
                        .kind = ParamKind::Int,
                        .default_value = 8,
                        .min_value = 1,
                        .max_value = 256,
                        .doc = "fewest samples"},
                       {.name = "max_samples",
                        .kind = ParamKind::Int,
                        .default_value = 32,
                        .min_value = 1,
                        .max_value = 256,
                        .doc = "most samples"}},
            .contract = {.answer = Answer::Approximation,
                         .max_fetches = [](const RayQuery&) { return 0.0; },
                         .max_fetches_formula = "0 (it draws nothing)",
                         .ray_probe = false}};
  }
  static void validate(const ParamValues& p, const std::string& where) {
    if (p.at("min_samples") > p.at("max_samples"))
      throw ConfigError(where + ": min_samples must not exceed max_samples");
  }
  const TechniqueInfo& info() const override {
    static const TechniqueInfo i = describe();
    return i;
  }
  void render(const FrameInput&, RenderTarget::Kind) override {}
  std::vector<ProbeHit> probe(const ReliefMap&, const GpuRelief&, const std::vector<ProbeRay>& r,
                              glm::dvec2) override {
    return std::vector<ProbeHit>(r.size());
  }
};

// Registers T for the scope of a test, as RL_REGISTER_TECHNIQUE would.
template <typename T>
struct ScopedPlugin {
  ScopedPlugin() {
    TechniqueRegistrar<T> registrar(__FILE__, "T");
    (void)registrar;
  }
  ~ScopedPlugin() { TechniqueRegistry::instance().remove(T::describe().name); }
};

TechniqueEntry entry_with(TechniqueInfo info) {
  TechniqueEntry e;
  e.info = std::move(info);
  e.create = [](const ParamValues& p) { return std::make_unique<PairedSamples>(p); };
  e.source = "tests/test_registry.cpp";
  return e;
}

std::string refusal(TechniqueEntry e) {
  try {
    TechniqueRegistry::instance().add(std::move(e));
  } catch (const std::logic_error& err) {
    return err.what();
  }
  return "";
}

TEST(Registry, RefusesADuplicateNameNamingBothPlugins) {
  const size_t before = TechniqueRegistry::instance().names().size();
  TechniqueInfo copy = TechniqueRegistry::instance().find("relief")->info;
  const std::string message = refusal(entry_with(copy));
  EXPECT_NE(message.find("'relief' is registered twice"), std::string::npos) << message;
  EXPECT_NE(message.find("techniques/relief/relief.cpp"), std::string::npos) << message;
  EXPECT_NE(message.find("tests/test_registry.cpp"), std::string::npos) << message;
  EXPECT_EQ(TechniqueRegistry::instance().names().size(), before);
  // The original entry is intact.
  EXPECT_EQ(TechniqueRegistry::instance().find("relief")->info.title, copy.title);
}

TEST(Registry, RefusesInconsistentMetadata) {
  auto with_param = [](ParamSpec p) {
    TechniqueInfo info = PairedSamples::describe();
    info.name = "test_bad_metadata";
    info.params = {p};
    return entry_with(info);
  };
  const ParamSpec good = PairedSamples::describe().params[0];
  ParamSpec swapped = good;
  swapped.min_value = 256;
  swapped.max_value = 1;
  EXPECT_NE(refusal(with_param(swapped)).find("min 256"), std::string::npos);
  ParamSpec outside = good;
  outside.default_value = 0;
  EXPECT_NE(refusal(with_param(outside)).find("default 0"), std::string::npos);
  ParamSpec fractional = good;
  fractional.default_value = 2.5;
  EXPECT_NE(refusal(with_param(fractional)).find("whole number"), std::string::npos);
  ParamSpec wide_bool = good;
  wide_bool.kind = ParamKind::Bool;
  wide_bool.default_value = 1;
  EXPECT_NE(refusal(with_param(wide_bool)).find("bool ranges over [0, 1]"), std::string::npos);
  ParamSpec undocumented = good;
  undocumented.doc.clear();
  EXPECT_NE(refusal(with_param(undocumented)).find("doc"), std::string::npos);
  TechniqueInfo twice = PairedSamples::describe();
  twice.name = "test_bad_metadata";
  twice.params.push_back(twice.params[0]);
  EXPECT_NE(refusal(entry_with(twice)).find("declared twice"), std::string::npos);
  TechniqueInfo two_line_title = PairedSamples::describe();
  two_line_title.name = "test_bad_metadata";
  two_line_title.title = "Title\n| forged | row |";
  EXPECT_NE(refusal(entry_with(two_line_title)).find("title must be one line"), std::string::npos);
  TechniqueInfo bad_name = PairedSamples::describe();
  bad_name.name = "Test Plugin";
  EXPECT_NE(refusal(entry_with(bad_name)).find("lower-case"), std::string::npos);
  EXPECT_EQ(TechniqueRegistry::instance().find("test_bad_metadata"), nullptr);
}

TEST(Registry, RefusesAContractItCannotBeHeldTo) {
  auto with_contract = [](TechniqueContract c) {
    TechniqueInfo info = PairedSamples::describe();
    info.name = "test_bad_contract";
    info.contract = std::move(c);
    return entry_with(info);
  };
  const TechniqueContract good = PairedSamples::describe().contract;
  TechniqueContract unbounded = good;
  unbounded.max_fetches = nullptr;
  EXPECT_NE(refusal(with_contract(unbounded)).find("declare max_fetches"), std::string::npos);
  TechniqueContract stray_knob = good;
  stray_knob.knobs = {{"linear_steps"}};
  EXPECT_NE(refusal(with_contract(stray_knob)).find("knob 'linear_steps' is not a declared"),
            std::string::npos);
  TechniqueContract converging = good;
  converging.answer = Answer::Converging;
  EXPECT_NE(refusal(with_contract(converging)).find("names its knobs"), std::string::npos);
  converging.knobs = {{"max_samples"}};
  EXPECT_NE(refusal(with_contract(converging)).find("knob 'max_samples' a finest value"),
            std::string::npos);
  converging.finest = {{"max_samples", 512}};
  EXPECT_NE(refusal(with_contract(converging)).find("outside its range"), std::string::npos);
  converging.finest = {{"max_samples", 256}};
  converging.t_error = [](const RayQuery&) { return 0.0; };
  EXPECT_NE(refusal(with_contract(converging)).find("conditions in words"), std::string::npos);
  EXPECT_EQ(TechniqueRegistry::instance().find("test_bad_contract"), nullptr);
}

// A parameter is written as a rows.csv column: one named like a result column would give every
// row two columns of one name (the hostile-input campaign saw rows.csv emptied, exit 0).
TEST(Registry, RefusesAParameterNamedLikeAResultColumn) {
  for (const char* column : {"wrong_pct", "technique", "frame_ms"}) {
    TechniqueInfo info = PairedSamples::describe();
    info.name = "test_param_like_column";
    info.params[0].name = column;
    const std::string message = refusal(entry_with(info));
    EXPECT_NE(message.find(std::string("parameter '") + column +
                           "' is named like the rows.csv "
                           "column"),
              std::string::npos)
        << message;
  }
  TechniqueInfo column_like_param = PairedSamples::describe();
  column_like_param.name = "test_column_like_param";
  column_like_param.params.clear();
  column_like_param.columns = {{.name = "linear_steps", .unit = "", .meaning = "clash"}};
  const std::string message = refusal(entry_with(column_like_param));
  EXPECT_NE(message.find("declares a column 'linear_steps' named like technique '"),
            std::string::npos)
      << message;
  EXPECT_EQ(TechniqueRegistry::instance().find("test_param_like_column"), nullptr);
}

// A describe() that throws runs inside a plugin's static initialiser: the refusal names the
// class and its file instead of ending the process with an unnamed exception.
class ThrowingDescribe final : public PairedSamples {
 public:
  using PairedSamples::PairedSamples;
  static TechniqueInfo describe() { throw std::runtime_error("no config for this build"); }
};

TEST(Registry, ADescribeThatThrowsIsRefusedByName) {
  std::string sink;
  set_registration_error_sink(&sink);
  { TechniqueRegistrar<ThrowingDescribe> registrar(__FILE__, "ThrowingDescribe"); }
  set_registration_error_sink(nullptr);
  EXPECT_NE(sink.find("ThrowingDescribe::describe()"), std::string::npos) << sink;
  EXPECT_NE(sink.find("test_registry.cpp"), std::string::npos) << sink;
  EXPECT_NE(sink.find("threw: no config for this build"), std::string::npos) << sink;
}

// A plugin that breaks its promise is named on every cell a sweep measures, not only by the
// contract suite (which a plugin's author may never run): relief declaring a bound of 3.
TEST(Registry, AFetchBoundBrokenAtRunTimeIsNamedInTheRunLog) {
  auto& registry = TechniqueRegistry::instance();
  const TechniqueEntry original = *registry.find("relief");
  registry.remove("relief");
  TechniqueEntry understated = original;
  understated.info.contract.max_fetches = [](const RayQuery&) { return 3.0; };
  understated.info.contract.max_fetches_formula = "3";
  registry.add(understated);
  const std::string dir = test::scratch_dir("fetch-bound");
  fs::create_directories(dir);
  // The 4-cell sweep of the fault tests (relief at 8 and 16 steps on 32^2 bricks).
  const std::string text = read_text(test::write_small_sweep(dir, "images = false\n"));
  try {
    test::run_sweep_in(text, dir);
  } catch (...) {
    registry.remove("relief");
    registry.add(original);
    throw;
  }
  registry.remove("relief");
  registry.add(original);
  std::ifstream in(dir + "/out/run.log");
  const std::string log((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(log.find("warning: relief ao_packed=0 binary_steps=5 color_mipmap=0 linear_steps=8 "
                     "mipmap=0: a fragment paid"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("fetches, over the 3 its describe() declares (3): its contract does not "
                     "hold on this cell"),
            std::string::npos)
      << log;
}

// A describe() counts samples of the map; a meta-relief combined per fetch reads every layer's
// texture for each sample, and the run-time check counts them so: relief keeps its promise on
// a two-layer meta-relief at the floor (every step taken: twice the bound in fetches), and no
// warning names it.
TEST(Registry, AMetaReliefCombinedPerFetchKeepsTheFetchBound) {
  const std::string dir = test::scratch_dir("fetch-bound-meta");
  fs::create_directories(dir);
  const std::string text = R"([sweep]
name = "meta-fetches"
elevations = [40]
viewports = [48]
images = false
frames = 1
warmup = 0

[[scene]]
name = "meta"
relief = { procedural = "constant", resolution = 32, options = { value = 1 } }
[scene.meta_relief]
combine = "runtime"
[[scene.meta_relief.layers]]
relief = { procedural = "constant", resolution = 32, options = { value = 1 } }
tiling = 2
weight = 0.3

[[technique]]
name = "relief"
linear_steps = [16]
binary_steps = [4]
)";
  test::run_sweep_in(text, dir);
  std::ifstream in(dir + "/out/run.log");
  const std::string log((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(log.find("1 cells"), std::string::npos) << log;
  EXPECT_EQ(log.find("its contract does not hold"), std::string::npos) << log;
}

// What a technique draws is set inclusion over the scene's inputs, one axis at a time, and the
// refusal is the first axis's own words.
TEST(Registry, WhatATechniqueDrawsIsSetInclusionOverTheScenesInputs) {
  SceneDesc scene;
  scene.base.kind = "plane";
  const Draws plain{};
  EXPECT_EQ(cannot_draw(plain, scene), "");
  scene.base.kind = "sphere";
  EXPECT_EQ(cannot_draw(plain, scene), "");
  const Draws planar{.bases = {BaseShape::Planar}};
  EXPECT_NE(cannot_draw(planar, scene).find("planar base only"), std::string::npos);
  scene.proxy = Proxy::Box;
  EXPECT_NE(cannot_draw(plain, scene).find("proxy = \"box\""), std::string::npos);
  const Draws boxed{.proxies = {Proxy::Base, Proxy::Box}};
  EXPECT_EQ(cannot_draw(boxed, scene), "");
  scene.relief.layers = 4;
  EXPECT_EQ(scene_inputs(scene).relief, Representation::Layers);
  const Draws single{.reads = {Representation::Heightfield}, .proxies = {Proxy::Box}};
  EXPECT_NE(cannot_draw(single, scene).find("no multilayer map"), std::string::npos);
  scene.relief.cells.active = true;  // the representation decides first
  EXPECT_EQ(scene_inputs(scene).relief, Representation::CellComplex);
  EXPECT_NE(cannot_draw(boxed, scene).find("the scene is a cell complex"), std::string::npos);
  const Draws cells{.reads = {Representation::CellComplex}, .proxies = {Proxy::Base, Proxy::Box}};
  EXPECT_EQ(cannot_draw(cells, scene), "");
  EXPECT_TRUE(cells.reads.only(Representation::CellComplex));
  EXPECT_EQ(reads_in_words(plain), "heightfield, layers");
  EXPECT_EQ(draws_on_in_words(boxed), "planar or curved base, or the relief's box proxy");
  // Every registered technique answers through the same declaration.
  for (const std::string& name : TechniqueRegistry::instance().names()) {
    const TechniqueInfo& info = TechniqueRegistry::instance().find(name)->info;
    EXPECT_EQ(cannot_render(info, scene), cannot_draw(info.draws, scene)) << name;
  }
}

TEST(Registry, ASharedParameterNameMeansOneQuantity) {
  // linear_steps is an int of relief's; a float of the same name would share its column.
  TechniqueInfo info = PairedSamples::describe();
  info.name = "test_shared_name";
  info.params[0].name = "linear_steps";
  info.params[0].kind = ParamKind::Float;
  const std::string message = refusal(entry_with(info));
  EXPECT_NE(message.find("'linear_steps'"), std::string::npos) << message;
  EXPECT_NE(message.find("one name, one quantity"), std::string::npos) << message;
  // The same kind is fine (relief and relief_silhouette share linear_steps).
  info.params[0].kind = ParamKind::Int;
  info.params[0].min_value = 1;
  EXPECT_EQ(refusal(entry_with(info)), "");
  TechniqueRegistry::instance().remove("test_shared_name");
}

TEST(ParamDefines, FollowFromTheDeclarations) {
  // ParamSpec::define: an int's value, a bool's 0 or 1, a float in parentheses; with
  // define_when_set, "1" where the value is not 0 and nothing at 0; no define, no entry.
  const std::vector<ParamSpec> specs = {
      {.name = "steps", .kind = ParamKind::Int, .max_value = 64, .doc = "", .define = "RL_STEPS"},
      {.name = "fix", .kind = ParamKind::Bool, .max_value = 1, .doc = "", .define = "RL_FIX"},
      {.name = "cells",
       .kind = ParamKind::Bool,
       .max_value = 1,
       .doc = "",
       .define = "RL_CELLS",
       .define_when_set = true},
      {.name = "bias",
       .kind = ParamKind::Float,
       .min_value = -1,
       .max_value = 1,
       .doc = "",
       .define = "RL_B"},
      {.name = "plain", .kind = ParamKind::Int, .max_value = 9, .doc = ""}};
  const std::map<std::string, std::string> on =
      param_defines(specs, {{"steps", 12}, {"fix", 1}, {"cells", 1}, {"bias", 0.25}, {"plain", 3}});
  const std::map<std::string, std::string> expected_on = {
      {"RL_STEPS", "12"}, {"RL_FIX", "1"}, {"RL_CELLS", "1"}, {"RL_B", "(0.250000)"}};
  EXPECT_EQ(on, expected_on);
  const std::map<std::string, std::string> off =
      param_defines(specs, {{"steps", 0}, {"fix", 0}, {"cells", 0}, {"bias", -0.5}, {"plain", 0}});
  const std::map<std::string, std::string> expected_off = {
      {"RL_STEPS", "0"}, {"RL_FIX", "0"}, {"RL_B", "(-0.500000)"}};
  EXPECT_EQ(off, expected_off);
}

TEST(TypedParams, AreReadAsDeclaredOrRefusedByName) {
  const std::vector<ParamSpec> specs = {
      {.name = "steps", .kind = ParamKind::Int, .max_value = 64, .doc = ""},
      {.name = "fix", .kind = ParamKind::Bool, .max_value = 1, .doc = ""},
      {.name = "bias", .kind = ParamKind::Float, .min_value = -1, .max_value = 1, .doc = ""}};
  const ParamValues values = {{"steps", 12}, {"fix", 1}, {"bias", 0.25}};
  EXPECT_EQ(typed_param<int>(specs, values, "steps", "technique 't'"), 12);
  EXPECT_TRUE(typed_param<bool>(specs, values, "fix", "technique 't'"));
  EXPECT_EQ(typed_param<double>(specs, values, "bias", "technique 't'"), 0.25);
  auto refusal = [&](auto read) {
    try {
      read();
    } catch (const std::logic_error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal([&] { typed_param<int>(specs, values, "fix", "technique 't'"); }),
            "technique 't' reads parameter 'fix' as int; it is declared bool");
  EXPECT_EQ(refusal([&] { typed_param<double>(specs, values, "step", "technique 't'"); }),
            "technique 't' reads parameter 'step', which it does not declare");
  EXPECT_EQ(refusal([&] { typed_param<int>(specs, {}, "steps", "technique 't'"); }),
            "technique 't' reads parameter 'steps', which has no value");
}

TEST(Registry, EveryLinearAndBinarySearchDeclaresItsStepsAlike) {
  // The search's two knobs come from linear_steps_param() and binary_steps_param(): one kind,
  // range and define wherever they appear (relief_robust's binary steps, which refine a step the
  // safety radius took, start at 1).
  const ParamSpec linear = linear_steps_param(8, ""), binary = binary_steps_param(5, "");
  int seen = 0;
  for (const std::string& name : TechniqueRegistry::instance().names()) {
    for (const ParamSpec& p : TechniqueRegistry::instance().find(name)->info.params) {
      if (p.name != "linear_steps" && p.name != "binary_steps") continue;
      SCOPED_TRACE(name + "." + p.name);
      const ParamSpec& shared = p.name == "linear_steps" ? linear : binary;
      ++seen;
      EXPECT_EQ(p.kind, shared.kind);
      EXPECT_EQ(p.max_value, shared.max_value);
      EXPECT_EQ(p.define, shared.define);
      if (name != "relief_robust") {
        EXPECT_EQ(p.min_value, shared.min_value);
      }
    }
  }
  EXPECT_GE(seen, 12);
}

const char* kPairedConfig = R"(
[sweep]
name = "paired"
elevations = [45]
viewports = [8]
frames = 1
warmup = 0
[[scene]]
name = "flat"
relief = { procedural = "flat", resolution = 8 }
[[technique]]
name = "test_paired_samples"
)";

TEST(Registry, ACrossParameterViolationIsAConfigErrorBeforeAnythingIsWritten) {
  ScopedPlugin<PairedSamples> plugin;
  const std::string dir = test::scratch_dir("violation");
  fs::create_directories(dir);
  // One bad setting among good ones in the product: 16 > 8.
  const std::string text = std::string(kPairedConfig) + "min_samples = [4, 16]\nmax_samples = 8\n";
  try {
    test::run_sweep_in(text, dir);
    FAIL() << "the violation was not caught";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("sweep.toml:11"), std::string::npos) << m;  // the [[technique]] line
    EXPECT_NE(m.find("min_samples = 16, max_samples = 8"), std::string::npos) << m;
    EXPECT_NE(m.find("must not exceed"), std::string::npos) << m;
  }
  EXPECT_FALSE(fs::exists(dir + "/out")) << "a rejected config wrote its output folder";
  // The registry's create() applies the same check.
  EXPECT_THROW(TechniqueRegistry::instance().create(
                   "test_paired_samples", {{"min_samples", 64}, {"max_samples", 8}}, "test"),
               ConfigError);
}

TEST(Registry, SetsPairValuesAndCombineWithTheLists) {
  ScopedPlugin<PairedSamples> plugin;
  const std::string text = std::string(kPairedConfig) +
                           "sets = [{ min_samples = 8, max_samples = 16 }, { min_samples = 32, "
                           "max_samples = 64 }, { max_samples = 4 }]\n";
  // The third set leaves min_samples at its default (8) > 4: rejected.
  EXPECT_THROW(parse_sweep_config(text, "paired.toml", "."), ConfigError);
  const std::string good = std::string(kPairedConfig) +
                           "sets = [{ min_samples = 8, max_samples = 16 }, { min_samples = 32, "
                           "max_samples = 64 }]\n";
  const SweepConfig config = parse_sweep_config(good, "paired.toml", ".");
  const std::vector<ParamValues> settings = parameter_settings(config.techniques[0]);
  ASSERT_EQ(settings.size(), 2u);  // paired, not 2 x 2
  EXPECT_EQ(settings[0], (ParamValues{{"min_samples", 8}, {"max_samples", 16}}));
  EXPECT_EQ(settings[1], (ParamValues{{"min_samples", 32}, {"max_samples", 64}}));
  EXPECT_EQ(expand_cells(config).size(), 2u);
  // A parameter is listed or in sets, not both.
  EXPECT_THROW(parse_sweep_config(good + "min_samples = [1, 2]\n", "paired.toml", "."),
               ConfigError);
  // Lists still combine as a product: relief's 2 x 3 settings.
  const SweepConfig product = parse_sweep_config(
      R"(
[sweep]
name = "product"
elevations = [45]
[[scene]]
name = "flat"
relief = { procedural = "flat", resolution = 8 }
[[technique]]
name = "relief"
linear_steps = [8, 16]
binary_steps = [0, 4, 8]
)",
      "product.toml", ".");
  const std::vector<ParamValues> grid = parameter_settings(product.techniques[0]);
  ASSERT_EQ(grid.size(), 6u);
  EXPECT_EQ(grid[1], (ParamValues{{"linear_steps", 8},
                                  {"binary_steps", 4},
                                  {"mipmap", 0},
                                  {"color_mipmap", 0},
                                  {"ao_packed", 0}}));
}

// A parameter added later with a neutral default (ParamSpec::neutral_default) leaves the keys of
// cells at that default as they were, so stored runs and committed reproductions still match:
// relief's mipmap, added after every results/ folder was measured.
TEST(Registry, ANeutralDefaultLeavesCellKeysAsTheyWere) {
  auto keys = [](const std::string& extra) {
    const SweepConfig c = parse_sweep_config(R"(
[sweep]
name = "keys"
elevations = [45]
[[scene]]
name = "flat"
relief = { procedural = "flat", resolution = 8 }
[[technique]]
name = "relief"
linear_steps = 16
)" + extra,
                                             "keys.toml", ".");
    return expand_cells(c).at(0).key;
  };
  // Pinned: the key this cell had before relief had a mipmap parameter (the one
  // results/ch5-fig5.12/rows.csv's relief rows were keyed by, by the same rule).
  EXPECT_EQ(keys(""), "610aed6f419cc9ab");
  EXPECT_EQ(keys("mipmap = 0\n"), keys(""));
  EXPECT_NE(keys("mipmap = 1\n"), keys(""));
}

// A sweep with the footprint truth writes columns one without it does not: its cells are others
// (a store must not resume one from the other), and without it keys are as they were.
TEST(Registry, AFootprintTruthKeysItsCellsApart) {
  auto key = [](const std::string& sweep_extra) {
    return expand_cells(parse_sweep_config("[sweep]\nname = \"keys\"\nelevations = [45]\n" +
                                               sweep_extra +
                                               "[[scene]]\nname = \"flat\"\nrelief = { "
                                               "procedural = \"flat\", resolution = 8 }\n"
                                               "[[technique]]\nname = \"relief\"\n"
                                               "linear_steps = 16\n",
                                           "keys.toml", "."))
        .at(0)
        .key;
  };
  EXPECT_EQ(key(""), "610aed6f419cc9ab");
  EXPECT_EQ(key("footprint_samples = 1\n"), key(""));
  EXPECT_NE(key("footprint_samples = 2\n"), key(""));
  EXPECT_NE(key("footprint_samples = 4\n"), key("footprint_samples = 2\n"));
}

}  // namespace
}  // namespace rl
