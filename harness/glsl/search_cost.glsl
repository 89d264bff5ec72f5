// What a fragment's search costs, counted as it runs (harness/metrics/fragment_cost.h):
// - rl_fetches: texture reads; every read of a technique goes through RL_FETCH (or adds its
//   reads here itself), so fetch counts compare across techniques;
// - rl_iterations: passes through a search loop's body -- one linear, binary or cone step, one
//   cell of a DDA, one quadtree node visited (a level change included), one slice. Where a step
//   reads several textures (multilayer groups, cube faces) or a level change reads none, the
//   two differ, and the loop work is what a GPU's ALUs pay.
int rl_fetches = 0;
int rl_iterations = 0;
#define RL_ITERATE (rl_iterations++)
#ifdef RL_COUNT_OPS
// What the fragment executed, by kind: in the op-counting form of the shader (gl/op_counting.h)
// every basic block adds its own ops to these where it begins (gl/spirv_op_counts.h), which
// also starts them at zero; rl_count_fragment() writes them out.
uint rl_ops_fetch;
uint rl_ops_float;
uint rl_ops_special;
uint rl_ops_int;
uint rl_ops_branch;
uint rl_ops_dynamic_index;
// The op-counting render (gl/op_count_buffer.h): per pixel, fragments and their ops by kind, in
// a buffer whose first two words are the frame's width and height (a pass drawn into a larger
// target of its own counts nothing outside the frame). A scene pass writes them as its
// fragment's last act (rl_count_fragment, gbuffer_outputs.glsl), a ray-probe pass as it writes
// its hit (probe_io.glsl).
layout(std430, binding = 0) coherent buffer RlOpCounts { uint rl_op_counts[]; };
void rl_write_op_counts() {
  uvec2 px = uvec2(gl_FragCoord.xy);
  if (px.x >= rl_op_counts[0] || px.y >= rl_op_counts[1]) return;
  uint at = 8u + (px.y * rl_op_counts[0] + px.x) * 8u;
  atomicAdd(rl_op_counts[at], 1u);
  atomicAdd(rl_op_counts[at + 1u], rl_ops_fetch);
  atomicAdd(rl_op_counts[at + 2u], rl_ops_float);
  atomicAdd(rl_op_counts[at + 3u], rl_ops_special);
  atomicAdd(rl_op_counts[at + 4u], rl_ops_int);
  atomicAdd(rl_op_counts[at + 5u], rl_ops_branch);
  atomicAdd(rl_op_counts[at + 6u], rl_ops_dynamic_index);
}
#endif
