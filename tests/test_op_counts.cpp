// Op counts (gl/spirv_op_counts.h, gl/op_counting.h, metrics/op_cost.h): a shader whose work is
// known, run in its op-counting form on GL, counts exactly that work, per lane and per 8 x 4
// lockstep group; the SPIR-V pass classifies each instruction as documented.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "gl/context.h"
#include "gl/op_count_buffer.h"
#include "gl/op_counting.h"
#include "gl/render_target.h"
#include "gl/shader_library.h"
#include "gl/spirv_op_counts.h"
#include "metrics/op_cost.h"

namespace rl {
namespace {

constexpr int kWidth = 16, kHeight = 8;

struct LoopCase {
  int steps = 5, extra = 0, discard_below = 0;
};

// The counts of one draw of tests/glsl/op_count_loop.glsl over a kWidth x kHeight frame.
PixelOpCounts draw_counted(const LoopCase& c) {
  GlContext::shared();
  OpCountingScope counting;
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
