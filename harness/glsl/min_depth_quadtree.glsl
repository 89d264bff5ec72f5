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
// What the stored bounds are lowered by (relief/min_depth_pyramid.h's default margin).
#define RL_MIN_DEPTH_MARGIN 1e-6

// Row of the atlas where level k (>= 1) starts.
int rl_level_row(int level, ivec2 map_size) { return map_size.y - (map_size.y >> (level - 1)); }

// The four nodes of the last 2 x 2 block read (one gather): a ray that moves on to a sibling
// finds its bound here without another read.
vec4 rl_sibling_bounds;
ivec3 rl_sibling_block = ivec3(-1);  // (parent x, parent y, level) of rl_sibling_bounds

#if defined(RL_BLOCK_CELLS) || defined(RL_BYTE_BOUNDS)
uniform bool rl_blocks_built;  // the packed blocks exist (8-bit maps)
#endif

#ifdef RL_BYTE_BOUNDS
// Levels 1 .. top - 2 as blocks of 4 x 4 nodes' bounds, 8 bits each
// (technique/quadtree_technique.cpp): level l's blocks start at row (H >> 2) - (H >> (l + 1)).
layout(binding = 6) uniform usampler2D rl_bound_blocks;
uvec4 rl_bytes;                   // the last block read
ivec3 rl_bytes_key = ivec3(-1);  // (block x, block y, level) of rl_bytes

// Byte (x, y) of a block, x and y in 0..3.
float rl_block_byte(ivec2 i) {
  int n = 4 * i.y + i.x;
  uint word = n < 4 ? rl_bytes.x : (n < 8 ? rl_bytes.y : (n < 12 ? rl_bytes.z : rl_bytes.w));
  return float((word >> uint(8 * (n & 3))) & 255u);
}

// Bound of `node` at `level` from a block: the one read last where it holds the node (or its
// children), else the block of the node's children (one level down, so that the descent into
// them is already read), or of the node itself at level 1. False where no block holds it.
bool rl_byte_bound(ivec2 node, int level, ivec2 map_size, int top, out float bound) {
  if (rl_bytes_key.z != level && rl_bytes_key.z != level - 1 ||
      any(notEqual(rl_bytes_key.z == level ? node >> 2 : node >> 1, rl_bytes_key.xy))) {
    int below = max(level - 1, 1);
    if (below + 2 > top) return false;
    ivec2 block = below == level ? node >> 2 : node >> 1;
    rl_fetches++;
    rl_bytes = texelFetch(rl_bound_blocks,
                          block + ivec2(0, (map_size.y >> 2) - (map_size.y >> (below + 1))), 0);
    rl_bytes_key = ivec3(block, below);
  }
  float least;
  if (rl_bytes_key.z == level) {
    least = rl_block_byte(node & 3);
  } else {  // the node's four children
    ivec2 c = (2 * node) & 3;
    least = min(min(rl_block_byte(c), rl_block_byte(c + ivec2(1, 0))),
                min(rl_block_byte(c + ivec2(0, 1)), rl_block_byte(c + ivec2(1, 1))));
  }
  bound = least / 255.0 - RL_MIN_DEPTH_MARGIN;
  return true;
}
#endif

// Bound of `node` (wrapped into the map) at `level` >= 1.
float rl_node_bound(ivec2 node, int level, ivec2 map_size, int top) {
#ifdef RL_BYTE_BOUNDS
  float from_bytes;
  if (rl_blocks_built && rl_byte_bound(node, level, map_size, top, from_bytes)) return from_bytes;
#endif
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

#ifdef RL_BLOCK_CELLS
// Level 1's nodes as their 3 x 3 corner depths, 8 bits each (technique/quadtree_technique.cpp),
// built on 8-bit maps only.
layout(binding = 5) uniform usampler2D rl_cell_blocks;

// Corner depth (a, b) of a block, a and b in 0..2.
float rl_block_depth(uvec4 block, int a, int b) {
  int n = 3 * b + a;
  uint word = n < 4 ? block.x : (n < 8 ? block.y : block.z);
  return float((word >> uint(8 * (n & 3))) & 255u) / 255.0;
}

// The first hit in the level-1 node at `lo` (cells lo .. lo + 1; `wrapped` is the node wrapped
// into the map) over [t, t_exit]: the cells the ray crosses there, each solved exactly, from one
// fetch.
bool rl_block_hit(ivec2 wrapped, ivec2 lo, vec2 start, vec2 dir, float z0, float t,
                  float t_exit, out float t_hit) {
  rl_fetches++;
  uvec4 block = texelFetch(rl_cell_blocks, wrapped, 0);
  ivec2 cell = clamp(ivec2(floor(start + dir * t)), lo, lo + 1);
  for (int k = 0; k < 3; k++) {  // a ray crosses at most 3 of the 4 cells
    vec2 t_axis = rl_exit_t(start, dir, vec2(cell), vec2(cell + 1));
    float t_out = max(min(min(t_axis.x, t_axis.y), t_exit), t);
    ivec2 o = cell - lo;
    vec4 corners = vec4(rl_block_depth(block, o.x, o.y), rl_block_depth(block, o.x + 1, o.y),
                        rl_block_depth(block, o.x, o.y + 1), rl_block_depth(block, o.x + 1, o.y + 1));
    float tau = rl_patch_first_hit(corners, start + dir * t - vec2(cell), dir, z0 + t, t_out - t);
    if (tau >= 0.0) {
      t_hit = t + tau;
      return true;
    }
    if (t_out >= t_exit) break;
    t = t_out;
    cell += t_axis.x <= t_axis.y ? ivec2(dir.x > 0.0 ? 1 : -1, 0) : ivec2(0, dir.y > 0.0 ? 1 : -1);
    if (any(lessThan(cell, lo)) || any(greaterThan(cell, lo + 1))) break;
  }
  return false;
}
#endif

// First t in [0, t_end] at which the ray p + t s (s.z = 1) meets the surface.
bool rl_quadtree_search(vec3 p, vec3 s, float t_end, out float t_hit) {
  const ivec2 map_size = textureSize(rl_relief, 0);
  // The map repeats: start in the first tile, where texel-centre coordinates are small.
  vec2 start = fract(p.xy) * vec2(map_size) - 0.5;
  vec2 dir = s.xy * vec2(map_size);
  const int top = rl_quadtree_top;
  // Start at the level whose nodes span the ray's whole lateral travel: the levels above it
  // could only send the search back down (a steep ray stays within a few cells). A technique
  // may start lower (RL_START_LEVEL): a hit near the entry is then found without descending
  // from the top, and a far one costs the climb instead (one level per node left).
  float travel = max(abs(dir.x), abs(dir.y)) * t_end;
  int level = clamp(int(ceil(log2(max(travel, 1.0)))), 0, top);
#ifdef RL_START_LEVEL
  level = min(level, RL_START_LEVEL);
#endif
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
      ivec2 wrapped = node - nodes * ivec2(floor(vec2(node) / vec2(nodes)));
      float bound = rl_node_bound(wrapped, level, map_size, top);
      bool reaches = p.z + t_exit >= bound;
#ifdef RL_BLOCK_CELLS
      if (reaches && level == 1 && rl_blocks_built) {
        // The node's four cells from one fetch, solved in the order the ray crosses them.
        if (rl_block_hit(wrapped, lo, start, dir, p.z, max(t, bound - p.z), t_exit, t_hit))
          return true;
        reaches = false;
      }
#endif
      if (reaches) {
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
