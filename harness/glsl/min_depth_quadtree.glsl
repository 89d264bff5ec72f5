// Hierarchical empty-space skipping over a min-depth quadtree of the bilinear cells
// (harness/relief/min_depth_pyramid.h; Tevs, Ihrke & Seidel 2008's maximum mipmaps in
// ReliefLab's depth convention). The ray descends into a node only where its depth can reach
// the node's bound inside the node, advancing to the depth of the bound first; elsewhere it
// jumps to the node's exit and climbs a level when it leaves the parent. At level 0 the
// including technique's rl_cell_hit decides the ray against one cell.
//
// The current cell is integer state: on leaving a node the ray steps out on the exit axis by
// whole cells and only the other axis is read from the position (clamped into the node it is
// still in), so rounding can neither stall the loop nor skip a node.
#include "harness/glsl/bilinear_walk.glsl"

// R32F, levels 1 and up stacked in rows: level k's (W >> k) x (H >> k) nodes start at row
// H - (H >> (k - 1)). One texture level read at lod 0, not a mip level per quadtree level:
// with texelFetch(.., level) rays came out right alone but wrong among 2,048 others on
// llvmpipe (the level then differs between fragments shaded together).
layout(binding = 4) uniform sampler2D rl_min_depth;
uniform int rl_quadtree_top;  // coarsest level (0: the map does not halve; the walk alone)

// Row of the atlas where level k (>= 1) starts.
int rl_level_row(int level, ivec2 map_size) { return map_size.y - (map_size.y >> (level - 1)); }

// The four nodes of the last 2 x 2 block read (one gather): a ray that moves on to a sibling
// finds its bound here without another read.
vec4 rl_sibling_bounds;
ivec3 rl_sibling_block = ivec3(-1);  // (parent x, parent y, level) of rl_sibling_bounds

// Bound of `node` (wrapped into the map) at `level` >= 1.
float rl_node_bound(ivec2 node, int level, ivec2 map_size, int top) {
  if (level == top) {  // no parent level: one texel
    rl_fetches++;
    return texelFetch(rl_min_depth, node + ivec2(0, rl_level_row(level, map_size)), 0).r;
  }
  ivec2 parent = node >> 1;
  ivec3 block = ivec3(parent, level);
  if (block != rl_sibling_block) {
    // Below the top a level's sides are even, so the block lies inside the level's rows.
    rl_fetches++;
    vec2 corner = vec2(2 * parent + ivec2(1, 1 + rl_level_row(level, map_size)));
    rl_sibling_bounds = textureGather(rl_min_depth, corner / vec2(textureSize(rl_min_depth, 0)), 0);
    rl_sibling_block = block;
  }
  // textureGather order: (x0, y1), (x1, y1), (x1, y0), (x0, y0).
  ivec2 child = node - 2 * parent;
  return child.y == 0 ? (child.x == 0 ? rl_sibling_bounds.w : rl_sibling_bounds.z)
                      : (child.x == 0 ? rl_sibling_bounds.x : rl_sibling_bounds.y);
}

// Iteration cap: every iteration descends, or leaves a node. Leaving nodes is bounded by the
// cells a ray crosses (RL_MAX_CELLS, as in the walk); descents by the levels per leave.
#ifndef RL_MAX_NODES
#define RL_MAX_NODES (4 * RL_MAX_CELLS)
#endif

// The finest level: the first t in [t, t_exit] at which the ray, whose start and direction are
// given in texel-centre coordinates (X = u * width - 0.5), meets the surface over `cell`.
// z0: the ray's depth at t = 0. Defined by the technique.
bool rl_cell_hit(ivec2 cell, vec2 start, vec2 dir, float z0, float t, float t_exit,
                 out float t_hit);

// t at which a ray from `start` along `dir` leaves the box [lo, hi] along x and along y.
vec2 rl_exit_t(vec2 start, vec2 dir, vec2 lo, vec2 hi) {
  return vec2(dir.x > 0.0 ? (hi.x - start.x) / dir.x
                          : (dir.x < 0.0 ? (lo.x - start.x) / dir.x : RL_NEVER),
              dir.y > 0.0 ? (hi.y - start.y) / dir.y
                          : (dir.y < 0.0 ? (lo.y - start.y) / dir.y : RL_NEVER));
}

// First t in [0, t_end] at which the ray p + t s (s.z = 1) meets the surface.
bool rl_quadtree_search(vec3 p, vec3 s, float t_end, out float t_hit) {
  const ivec2 map_size = textureSize(rl_relief, 0);
  // The map repeats: start in the first tile, where texel-centre coordinates are small.
  vec2 start = fract(p.xy) * vec2(map_size) - 0.5;
  vec2 dir = s.xy * vec2(map_size);
  const int top = rl_quadtree_top;
  // Start at the level whose nodes span the ray's whole lateral travel: the levels above it
  // could only send the search back down (a steep ray stays within a few cells).
  float travel = max(abs(dir.x), abs(dir.y)) * t_end;
  int level = clamp(int(ceil(log2(max(travel, 1.0)))), 0, top);
  ivec2 cell = ivec2(floor(start));
  float t = 0.0;
  for (int n = 0; n < RL_MAX_NODES; n++) {
    RL_ITERATE;
    ivec2 node = cell >> level;  // arithmetic shift: floor division, also below 0
    ivec2 lo = node << level, hi = (node + 1) << level;
    // t at which the ray leaves the node along each axis.
    vec2 t_axis = rl_exit_t(start, dir, vec2(lo), vec2(hi));
    float t_exit = max(min(min(t_axis.x, t_axis.y), t_end), t);
    if (level > 0) {
      // Wrap into the map (GLSL's % is undefined for negative operands).
      ivec2 nodes = map_size >> level;
      float bound = rl_node_bound(node - nodes * ivec2(floor(vec2(node) / vec2(nodes))), level,
                                  map_size, top);
      if (p.z + t_exit >= bound) {
        // The ray can reach the node's highest point inside it: go down to where it does.
        t = max(t, bound - p.z);
        level--;
        cell = clamp(ivec2(floor(start + dir * t)), lo, hi - 1);
        continue;
      }
    } else if (rl_cell_hit(cell, start, dir, p.z, t, t_exit, t_hit)) {
      return true;
    }
    if (t_exit >= t_end) break;
    // Leave the node: whole cells on the exit axis, the other axis from the position.
    t = t_exit;
    ivec2 beyond = ivec2(dir.x > 0.0 ? hi.x : lo.x - 1, dir.y > 0.0 ? hi.y : lo.y - 1);
    ivec2 within = clamp(ivec2(floor(start + dir * t)), lo, hi - 1);
    ivec2 next = t_axis.x <= t_axis.y ? ivec2(beyond.x, within.y) : ivec2(within.x, beyond.y);
    cell = next;
    if (level < top && any(notEqual(next >> (level + 1), node >> 1))) level++;
  }
  t_hit = t_end;
  return false;
}
