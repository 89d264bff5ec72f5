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
#endif
