// Op counts (gl/spirv_op_counts.h, gl/op_counting.h, metrics/op_cost.h): a shader whose work is
// known, run in its op-counting form on GL, counts exactly that work, per lane and per 8 x 4
// lockstep group; the SPIR-V pass classifies each instruction as documented.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/op_kinds.h"
#include "gl/context.h"
#include "gl/op_count_buffer.h"
#include "gl/op_counting.h"
#include "gl/render_target.h"
#include "gl/shader_library.h"
#include "gl/spirv_op_counts.h"
#include "metrics/op_cost.h"
#include "relief/procedural.h"
#include "support/test_support.h"
#include "technique/technique.h"

namespace rl {
namespace {

constexpr int kWidth = 16, kHeight = 8;

struct LoopCase {
  int steps = 5, extra = 0, discard_below = 0;
  int group_stride = 1;
};

// The counts of one draw of tests/glsl/op_count_loop.glsl over a kWidth x kHeight frame.
PixelOpCounts draw_counted(const LoopCase& c) {
  GlContext::shared();
  OpCountingScope counting(c.group_stride);
  ProgramDesc d;
  d.owner = "op_count_test";
  d.vertex_file = "harness/glsl/fullscreen.vert";
  d.fragment_files = {"tests/glsl/op_count_loop.glsl"};
  const GLuint program = ShaderLibrary::shared().program(d);
  GLuint texture = 0, vao = 0;
  const float texels[4] = {0.25f, 0.5f, 0.75f, 1.0f};
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  glTextureStorage2D(texture, 1, GL_R32F, 4, 1);
  glTextureSubImage2D(texture, 0, 0, 0, 4, 1, GL_RED, GL_FLOAT, texels);
  glBindTextureUnit(0, texture);
  glCreateVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glUseProgram(program);
  // Set by name: the op-counting form keeps the names the harness sets uniforms by.
  glUniform1i(glGetUniformLocation(program, "rl_test_map"), 0);
  glUniform1i(glGetUniformLocation(program, "rl_test_steps"), c.steps);
  glUniform1i(glGetUniformLocation(program, "rl_test_extra"), c.extra);
  glUniform1i(glGetUniformLocation(program, "rl_test_discard_below"), c.discard_below);
  RenderTarget target(kWidth, kHeight, RenderTarget::Kind::ColorOnly);
  target.bind_and_clear();
  OpCountBuffer ops(kWidth, kHeight);
  ops.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  PixelOpCounts out = ops.read_back();
  out.group_stride = c.group_stride;
  glDeleteVertexArrays(1, &vao);
  glDeleteTextures(1, &texture);
  return out;
}

uint32_t at(const PixelOpCounts& c, OpKind kind, int x, int y) {
  return c.ops[int(kind)][size_t(y) * c.width + x];
}

TEST(OpCounts, EachLaneCountsTheLoopItRan) {
  const PixelOpCounts five = draw_counted({5, 0, 0});
  const PixelOpCounts nine = draw_counted({9, 0, 0});
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      SCOPED_TRACE("pixel " + std::to_string(x) + "," + std::to_string(y));
      EXPECT_EQ(five.fragments[size_t(y) * kWidth + x], 1u);
      EXPECT_EQ(at(five, OpKind::Fetch, x, y), 5u);
      EXPECT_EQ(at(nine, OpKind::Fetch, x, y), 9u);
      // Four more steps: each a multiply and an add; an integer compare, increment and i % 4;
      // and the loop's conditional branch.
      EXPECT_EQ(at(nine, OpKind::Float, x, y) - at(five, OpKind::Float, x, y), 8u);
      EXPECT_EQ(at(nine, OpKind::Int, x, y) - at(five, OpKind::Int, x, y), 12u);
      EXPECT_EQ(at(nine, OpKind::Branch, x, y) - at(five, OpKind::Branch, x, y), 4u);
      EXPECT_EQ(at(five, OpKind::Special, x, y), 1u);  // the square root
      EXPECT_EQ(at(five, OpKind::DynamicIndex, x, y), 0u);
    }
}

TEST(OpCounts, A32LaneGroupPaysItsSlowestLane) {
  const PixelOpCounts c = draw_counted({5, 8, 0});
  EXPECT_EQ(at(c, OpKind::Fetch, 3, 0), 13u);
  EXPECT_EQ(at(c, OpKind::Fetch, 4, 0), 5u);
  const OpCost cost = op_cost(c);
  // One lane in eight runs 13 steps: every lane of its 8 x 4 tile waits for it.
  EXPECT_DOUBLE_EQ(cost.warp_ops_per_px[int(OpKind::Fetch)], 13.0);
  EXPECT_DOUBLE_EQ(cost.counted_fragments, double(kWidth * kHeight));
}

TEST(OpCounts, DiscardedFragmentsCountWhatTheyRan) {
  const PixelOpCounts c = draw_counted({5, 0, 8});
  for (int x = 0; x < kWidth; ++x) {
    EXPECT_EQ(c.fragments[size_t(x)], 1u) << x;
    EXPECT_EQ(at(c, OpKind::Fetch, x, 0), 5u) << x;
    EXPECT_EQ(at(c, OpKind::Special, x, 0), x < 8 ? 0u : 1u) << x;  // no sqrt after a discard
  }
}

TEST(OpCounts, AStrideCountsOnlyItsGroupsAndEachExactly) {
  // Rows 0-3 and columns 0-7 make group (0, 0), the only one of the four a stride of 2 counts.
  const PixelOpCounts all = draw_counted({5, 8, 0, 1});
  const PixelOpCounts sampled = draw_counted({5, 8, 0, 2});
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      SCOPED_TRACE("pixel " + std::to_string(x) + "," + std::to_string(y));
      const size_t i = size_t(y) * kWidth + x;
      const bool counted = x < kWarpTileWidth && y < kWarpTileHeight;
      EXPECT_EQ(sampled.fragments[i], counted ? 1u : 0u);
      // The gate's own work is not counted: a counted pixel's counts are the ungated ones.
      for (int k = 0; k < kOpKinds; ++k)
        EXPECT_EQ(sampled.ops[k][i], counted ? all.ops[k][i] : 0u) << kOpKindNames[k];
    }
  // The sample's mean stands for the frame: every group here pays the same.
  const OpCost whole = op_cost(all), sample = op_cost(sampled);
  for (int k = 0; k < kOpKinds; ++k)
    EXPECT_DOUBLE_EQ(sample.warp_ops_per_px[k], whole.warp_ops_per_px[k]) << kOpKindNames[k];
  EXPECT_DOUBLE_EQ(sample.counted_fragments, double(kWarpTileWidth * kWarpTileHeight));
}

TEST(OpCounts, AStridedCostIsTheMeanOfTheGroupsItCounted) {
  // 16 x 8 pixels with a stride of 2: groups (0, 0) counted, (1, 0), (0, 1), (1, 1) not.
  PixelOpCounts c;
  c.width = kWidth;
  c.height = kHeight;
  c.group_stride = 2;
  c.fragments.assign(size_t(kWidth) * kHeight, 1);
  for (auto& kind : c.ops) kind.assign(size_t(kWidth) * kHeight, 0);
  auto fetches = [&](int x, int y) -> uint32_t& { return c.ops[0][size_t(y) * kWidth + x]; };
  fetches(2, 1) = 10;   // the slowest lane of the counted group
  fetches(12, 6) = 99;  // in a group the stride leaves out: ignored
  const OpCost cost = op_cost(c);
  EXPECT_DOUBLE_EQ(cost.warp_ops_per_px[0], 10.0);
  EXPECT_DOUBLE_EQ(cost.counted_fragments, 32.0);
}

TEST(OpCounts, AProbePassCountsEachRayAtItsPixel) {
  // A ray-probe pass in its op-counting form writes each ray's ops at the ray's pixel (rows of
  // up to 1024 rays): relief's search reads the map through RL_FETCH alone, so each ray's fetch
  // ops are its own fetches plus the two reads of its origin and direction.
  const ReliefMap map = make_procedural("sines", 32, {}, 10.0, "test");
  const std::vector<ProbeRay> rays =
      test::as_probe_rays(test::random_tangent_rays(1500, 20, 80, 0.08, 5, 0.0));
  const ParamValues params = {{"linear_steps", 16}, {"binary_steps", 4}};
  const std::vector<ProbeHit> hits = test::probe("relief", params, map, rays);
  GlContext::shared();
  GpuRelief relief(map);
  auto t = TechniqueRegistry::instance().create("relief", params, "test");
  t->prepare(map);
  OpCountBuffer ops(1024, 2);
  ops.bind();
  {
    OpCountingScope counting(1);
    (void)t->probe(map, relief, rays, glm::dvec2(0.08));
  }
  const PixelOpCounts counts = ops.read_back();
  for (size_t i = 0; i < 2048; ++i) {
    const int x = int(i % 1024), y = int(i / 1024);
    if (i >= rays.size()) {
      EXPECT_EQ(counts.fragments[i], 1u) << "padding pixel " << i;  // shaded, no ray
      continue;
    }
    ASSERT_EQ(counts.fragments[i], 1u) << "ray " << i;
    EXPECT_EQ(at(counts, OpKind::Fetch, x, y), uint32_t(hits[i].fetches + 2)) << "ray " << i;
  }
}

TEST(OpCounts, InstructionsAreClassifiedByKindAndWidth) {
  const std::string source = R"(#version 450 core
layout(location = 0) out vec4 o_color;
uniform sampler2D map;
uniform vec4 a;
uniform ivec2 b;
void main() {
  vec4 t = texture(map, a.xy);           // fetch 1
  vec4 f = a * t + a;                    // float 4 + 4
  float s = inversesqrt(f.x) / f.y;      // special 1 + 1
  ivec2 i = (b << 1) & ivec2(7);         // int 2 + 2
  float local[4] = float[4](1.0, 2.0, 3.0, 4.0);
  o_color = vec4(s + local[i.x]);        // float 1, dynamic index 1
})";
  OpCounts total{};
  for (const OpCounts& block : block_op_counts(fragment_spirv(source)))
    for (int k = 0; k < kOpKinds; ++k) total[k] += block[k];
  EXPECT_EQ(total[int(OpKind::Fetch)], 1u);
  EXPECT_EQ(total[int(OpKind::Float)], 9u);
  EXPECT_EQ(total[int(OpKind::Special)], 2u);
  EXPECT_EQ(total[int(OpKind::Int)], 4u);
  EXPECT_EQ(total[int(OpKind::Branch)], 0u);
  EXPECT_EQ(total[int(OpKind::DynamicIndex)], 1u);
}

TEST(OpCounts, TheHarnessesOwnCountersAreNotCounted) {
  // rl_fetches and rl_iterations feed the G-buffer's cost columns; in the timed program nothing
  // reads them and a GPU compiler drops their increments. The loop's own counter still counts.
  const std::string source = R"(#version 450 core
layout(location = 0) out vec4 o_color;
int rl_fetches = 0;
int rl_iterations = 0;
uniform int n;
void main() {
  for (int i = 0; i < n; i++) {  // int 2: the compare and the increment
    rl_iterations++;
    rl_fetches += 2;
  }
  o_color = vec4(float(rl_fetches));  // float 1: the conversion of a value that is read
})";
  OpCounts total{};
  for (const OpCounts& block : block_op_counts(fragment_spirv(source)))
    for (int k = 0; k < kOpKinds; ++k) total[k] += block[k];
  EXPECT_EQ(total[int(OpKind::Int)], 2u);
  EXPECT_EQ(total[int(OpKind::Float)], 1u);
}

TEST(OpCounts, AShaderWithoutCountersIsRefusedByName) {
  const std::string source =
      "#version 450 core\nlayout(location = 0) out vec4 o;\n"
      "void main() { o = vec4(1.0); }\n";
  try {
    op_counting_glsl(source);
    FAIL() << "instrumented a shader with no counters";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("rl_ops_"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rl
