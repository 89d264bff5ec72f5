// Walking a ray over texel-centre cells (Baboud & Decoret 2006, Section 3.3, after
// Amanatides & Woo 1987). Coordinates X = u * width - 0.5, Y = v * height - 0.5 put texel
// centres on integers: lines X = i and Y = j are the "centerlines", cell (i, j) =
// [i, i+1] x [j, j+1] holds one bilinear patch. A walk state gives the parameter t at which
// the ray next crosses a vertical and a horizontal centerline.
#include "harness/glsl/relief_common.glsl"

// Hard cap on cells per ray, whatever the view: loops stay bounded even for rays nearly
// parallel to the base. A ray that reaches it reports no hit.
#ifndef RL_MAX_CELLS
#define RL_MAX_CELLS 16384
#endif

const float RL_NEVER = 3.0e38;  // t of a crossing that never comes (direction component 0)

struct RlWalk {
  vec2 start;   // ray origin in texel-centre coordinates, wrapped near the origin
  vec2 dir;     // ray direction in texel-centre units per unit t
  ivec2 cell;   // current cell
  ivec2 step;   // +1, -1 or 0 per axis
  vec2 next;    // t of the next vertical / horizontal centerline crossing
  vec2 delta;   // t between consecutive crossings per axis
};

RlWalk rl_walk_begin(vec3 p, vec3 s) {
  vec2 size = vec2(textureSize(rl_relief, 0));
  RlWalk w;
  // Wrap the origin into the first tile: the map repeats, and small coordinates keep the
  // per-cell arithmetic at float precision.
  w.start = fract(p.xy) * size - 0.5;
  w.dir = s.xy * size;
  w.cell = ivec2(floor(w.start));
  for (int a = 0; a < 2; a++) {
    if (w.dir[a] > 0.0) {
      w.step[a] = 1;
      w.delta[a] = 1.0 / w.dir[a];
      w.next[a] = (float(w.cell[a] + 1) - w.start[a]) / w.dir[a];
    } else if (w.dir[a] < 0.0) {
      w.step[a] = -1;
      w.delta[a] = -1.0 / w.dir[a];
      w.next[a] = (w.start[a] - float(w.cell[a])) / -w.dir[a];
    } else {
      w.step[a] = 0;
      w.delta[a] = RL_NEVER;
      w.next[a] = RL_NEVER;
    }
  }
  return w;
}

// Moves to the next cell; returns the t at which it is entered.
float rl_walk_advance(inout RlWalk w) {
  if (w.next.x <= w.next.y) {
    float t = w.next.x;
    w.cell.x += w.step.x;
    w.next.x += w.delta.x;
    return t;
  }
  float t = w.next.y;
  w.cell.y += w.step.y;
  w.next.y += w.delta.y;
  return t;
}

// Texture coordinate of a point given in texel-centre coordinates of the wrapped start.
vec2 rl_walk_uv(RlWalk w, vec2 X) { return (X + 0.5) / vec2(textureSize(rl_relief, 0)); }
