// A deliberately broken intersection routine: the shader-error test expects the compile
// error to name this file and line 7.
#include "harness/glsl/relief_common.glsl"

RlHit rl_intersect(vec3 p, vec3 s) {
  RlHit h = rl_hit_on_ray(p, s, 0.0, true);
  h.depth = undefined_symbol_on_line_7;
  return h;
}
