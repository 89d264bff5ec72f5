// GLSL composition, error messages and the program cache.
#include <algorithm>

#include <gtest/gtest.h>

#include "core/error.h"
#include "gl/context.h"
#include "gl/shader_library.h"

namespace rl {
namespace {

TEST(Context, IsOpenGl45Core) {
  GlContext& gl = GlContext::shared();
  EXPECT_FALSE(gl.renderer().empty());
  EXPECT_NE(gl.version().find("4.5"), std::string::npos) << gl.version();
}

TEST(Compose, ExpandsIncludesOnceWithLineDirectives) {
  ComposedSource s = compose_glsl({"techniques/relief/relief.glsl", "harness/glsl/probe_main.glsl"},
                                  {{"RL_LINEAR_STEPS", "8"}, {"RL_BINARY_STEPS", "3"}});
  EXPECT_EQ(s.text.rfind("#version 450 core\n", 0), 0u);
  EXPECT_NE(s.text.find("#define RL_LINEAR_STEPS 8"), std::string::npos);
  // relief_common.glsl is included by both files but appears once (with the search counters it
  // includes, search_cost.glsl); probe_main.glsl brings the probe pass's inputs and outputs
  // (probe_io.glsl).
  ASSERT_EQ(s.files.size(), 5u);
  EXPECT_EQ(s.files[1], "harness/glsl/relief_common.glsl");
  EXPECT_NE(std::find(s.files.begin(), s.files.end(), "harness/glsl/probe_io.glsl"), s.files.end());
  EXPECT_NE(std::find(s.files.begin(), s.files.end(), "harness/glsl/search_cost.glsl"),
            s.files.end());
  const std::string marker = "int rl_fetches = 0;";
  EXPECT_EQ(s.text.find(marker), s.text.rfind(marker));
  EXPECT_NE(s.text.find("#line 1 1\n"), std::string::npos);
}

TEST(Compose, MapsDriverLogsToFiles) {
  const std::vector<std::string> files = {"a.glsl", "b.glsl"};
  EXPECT_EQ(map_glsl_log("1:12(5): error: `x' undeclared\n", files),
            "b.glsl:12:5: error: `x' undeclared\n");
  EXPECT_EQ(map_glsl_log("0(7) : error C1008: undefined variable\n", files),
            "a.glsl:7: error C1008: undefined variable\n");
}

TEST(ShaderLibrary, CompileErrorNamesTechniqueFileAndLine) {
  GlContext::shared();
  ProgramDesc d;
  d.owner = "broken_test";
  d.vertex_file = "harness/glsl/base.vert";
  d.fragment_files = {"tests/glsl/broken_intersect.glsl", "harness/glsl/surface_main.glsl"};
  try {
    ShaderLibrary::shared().program(d);
    FAIL() << "broken shader compiled";
  } catch (const GlError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("technique 'broken_test'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("tests/glsl/broken_intersect.glsl:7"), std::string::npos) << msg;
  }
  d.fragment_files = {"techniques/nope/nope.glsl"};
  EXPECT_THROW(ShaderLibrary::shared().program(d), GlError);
}

TEST(ShaderLibrary, CompilesEachVariantOnce) {
  GlContext::shared();
  ShaderLibrary& lib = ShaderLibrary::shared();
  ProgramDesc d;
  d.owner = "relief";
  d.vertex_file = "harness/glsl/fullscreen.vert";
  d.fragment_files = {"techniques/relief/relief.glsl", "harness/glsl/probe_main.glsl"};
  d.defines = {{"RL_LINEAR_STEPS", "4"}, {"RL_BINARY_STEPS", "2"}, {"RL_PROBE", "1"}};
  const size_t before = lib.compiled_count();
  const GLuint p1 = lib.program(d);
  const GLuint p2 = lib.program(d);
  EXPECT_EQ(p1, p2);
  EXPECT_EQ(lib.compiled_count(), before + 1);
  d.defines["RL_LINEAR_STEPS"] = "5";
  EXPECT_NE(lib.program(d), p1);
  EXPECT_EQ(lib.compiled_count(), before + 2);
}

}  // namespace
}  // namespace rl
