// Hierarchical exact search (ReliefLab, beyond the published work): the min-depth quadtree of
// the bilinear cells skips empty space (harness/glsl/min_depth_quadtree.glsl); in every cell
// it reaches, the ray is solved exactly against the cell's bilinear patch, as
// relief_exact_bilinear does in every cell it walks. Same surface, same solve: the same first
// hit, at the cost of the cells the ray comes near rather than all it passes over.
#include "harness/glsl/min_depth_quadtree.glsl"

bool rl_cell_hit(ivec2 cell, vec2 start, vec2 dir, float z0, float t, float t_exit,
                 out float t_hit) {
  vec2 local = start + dir * t - vec2(cell);
  float tau = rl_patch_first_hit(rl_cell_corners(cell), local, dir, z0 + t, t_exit - t);
  t_hit = t + tau;
  return tau >= 0.0;
}

RlHit rl_intersect(vec3 p, vec3 s) {
  float t_hit;
  bool found = rl_quadtree_search(p, s, 1.0 - p.z, t_hit);
  return rl_hit_on_ray(p, s, t_hit, found);
}
