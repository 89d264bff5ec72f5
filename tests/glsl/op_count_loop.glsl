// A fragment whose ops are known (tests/test_op_counts.cpp): a loop of texelFetch reads, each
// scaled and summed (one float multiply and one add a step), rl_test_extra more steps on every
// eighth column (one lane of each 8-wide group), a discard on the columns rl_test_discard_below
// leaves out, and one square root.
#include "harness/glsl/gbuffer_outputs.glsl"
uniform sampler2D rl_test_map;
uniform int rl_test_steps;
uniform int rl_test_extra;
uniform int rl_test_discard_below;

void main() {
  int x = int(gl_FragCoord.x);
  int steps = rl_test_steps + (x % 8 == 3 ? rl_test_extra : 0);
  float acc = 0.0;
  for (int i = 0; i < steps; ++i) acc += texelFetch(rl_test_map, ivec2(i % 4, 0), 0).r * 2.0;
  if (x < rl_test_discard_below) RL_DISCARD
  o_color = vec4(sqrt(acc));
  rl_count_fragment();
}
