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
