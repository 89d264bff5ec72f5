#pragma once
// The op-counting form of a fragment shader (gl/spirv_op_counts.h): its composed GLSL compiled
// to SPIR-V by glslang, every basic block made to add what it executes to the rl_ops_* counters,
// and the result written back as GLSL 4.50 by SPIRV-Cross, so that every renderer -- llvmpipe
// included -- can run it. Names survive the round trip (the harness sets uniforms by name);
// locations glslang assigned to inputs and plain uniforms are dropped so that the vertex
// shader, compiled from its own source, still matches by name.
#include <cstdint>
#include <string>
#include <vector>

namespace rl {

// The instrumented GLSL of `fragment_source` (a composed source, #version first). With
// `group_stride` > 1 only one 8 x 4 lockstep group in group_stride^2 runs the pass -- those whose
// column and row of groups are multiples of it; the others discard before anything else, so a
// frame costs about that much less to count (metrics/op_cost.h scales the total back). Throws
// std::runtime_error with glslang's or SPIRV-Cross's log when a stage fails.
std::string op_counting_glsl(const std::string& fragment_source, int group_stride = 1);

// The SPIR-V glslang makes of `fragment_source` for OpenGL (locations and bindings assigned);
// for tests and for reading a shader's static op mix. Throws like op_counting_glsl.
std::vector<uint32_t> fragment_spirv(const std::string& fragment_source);

}  // namespace rl
