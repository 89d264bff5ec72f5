// Exact bilinear traversal (ReliefLab, beyond Baboud & Decoret 2006): the centerline walk of
// relief_exact, with every cell's bilinear patch solved exactly (harness/glsl/bilinear_walk.glsl).
// It finds the saddle intersections of the paper's Figure 3 that linear profiles miss, and
// reconstructs exactly the surface the truth (and GL_LINEAR) defines.
#include "harness/glsl/bilinear_walk.glsl"

RlHit rl_intersect(vec3 p, vec3 s) {
  float t_hit;
  bool found = rl_bilinear_walk(p, s, 0.0, 1.0 - p.z, t_hit);
  return rl_hit_on_ray(p, s, t_hit, found);
}
