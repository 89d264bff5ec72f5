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

// The instrumented GLSL of `fragment_source` (a composed source, #version first). Throws
// std::runtime_error with glslang's or SPIRV-Cross's log when a stage fails.
std::string op_counting_glsl(const std::string& fragment_source);

// The SPIR-V glslang makes of `fragment_source` for OpenGL (locations and bindings assigned);
// for tests and for reading a shader's static op mix. Throws like op_counting_glsl.
std::vector<uint32_t> fragment_spirv(const std::string& fragment_source);

}  // namespace rl
