#pragma once
// Dynamic instruction counts by kind, for the GPU cost model (metrics/op_cost.h): a pass over a
// fragment shader's SPIR-V that adds, where every basic block begins, what that block executes
// to one counter per kind (a block runs whole once entered). Run once, the instrumented shader
// leaves in each counter what its fragment executed -- loops, branches and early exits included --
// on any renderer.
//
// The counters are the shader's own Private `uint` globals, found by name (search_cost.glsl
// declares them under RL_COUNT_OPS and writes them out); a kind whose counter is not declared is
// not counted. What counts, per SPIR-V instruction (components: of the result, or of the
// operands for a dot product and the like):
// - fetch: a texture read (sample, fetch, gather, image load), 1 each;
// - float: float arithmetic, comparisons, conversions, derivatives and GLSL.std.450's cheap
//   functions (min, max, clamp, mix, floor, fract, fma, ...), per component;
// - special: what GPUs run on their special-function units -- division, sqrt, inversesqrt, exp,
//   log, pow, trigonometry -- per component (length and normalize add one beside their float
//   work);
// - int: integer and bit arithmetic, integer and boolean comparisons and logic, per component;
// - branch: a conditional branch, a switch, a discard;
// - dynamic_index: an access into a function's or the shader's own array at an index known only
//   at run time (an array a GPU may have to keep in memory rather than registers).
// Loads, stores, copies, composites, calls and returns are left out: a GPU compiler keeps
// locals in registers and inlines calls, so glslang's unoptimised SPIR-V overstates them.
// The harness's own bookkeeping is not counted either: increments of rl_fetches and
// rl_iterations (search_cost.glsl), which the timed program never reads, so that a GPU's
// compiler removes them. Functions named rl_uncounted_* count nothing: the harness's own code in
// the counting form (the gate that picks which lockstep groups are counted, gl/op_counting.h), not
// the pass's.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/op_kinds.h"

namespace rl {

// The GLSL name of each kind's counter, in OpKind's order (harness/glsl/search_cost.glsl).
inline const std::array<const char*, kOpKinds> kOpCounterNames = {
    "rl_ops_fetch", "rl_ops_float",  "rl_ops_special",
    "rl_ops_int",   "rl_ops_branch", "rl_ops_dynamic_index"};

inline constexpr const char* kUncountedPrefix = "rl_uncounted_";

// What each basic block of `spirv` executes, by kind, in the order the blocks appear (for tests
// and for reading a shader's static mix).
std::vector<OpCounts> block_op_counts(const std::vector<uint32_t>& spirv);

// `spirv` with every block adding its counts to the counters, which start at zero. Throws
// std::runtime_error when the module is malformed or declares no counter.
std::vector<uint32_t> add_op_counters(const std::vector<uint32_t>& spirv);

// `spirv` without the Location decorations of its inputs and plain (non-block) uniforms, nor the
// Binding decorations of plain uniforms that are not samplers or images: what glslang assigned
// for OpenGL SPIR-V, which GLSL written back from it must not carry (a float uniform takes no
// binding, and a fragment input with a location no longer matches a vertex output without one).
std::vector<uint32_t> without_assigned_locations(const std::vector<uint32_t>& spirv);

}  // namespace rl
