// Relief mapping on cubic cell complexes (Apaza & Andujar, Sections 3.2, 3.4 and 3.5.2): the
// cell table, the four projections, and the inside test of a point against the distance maps.
// harness/relief/cell_complex.cpp is the same on the CPU (configure_cell, project_in_cell,
// CellComplex::encoded_inside); gpu/gpu_cell_complex.cpp packs the textures.
//
// Points are in grid coordinates g = texture-space position * N: cell floor(g), local q in
// [0, 1]^3. Faces f = 2 * axis + side (0 = -u, 1 = +u, 2 = -v, 3 = +v, 4 = -depth, 5 = +depth);
// a face's map is indexed by its two other axes in cyclic order.

layout(binding = 4) uniform usampler3D rl_cell_table;      // x: packed cell bits, y: first face
layout(binding = 5) uniform sampler2DArray rl_cell_distance;  // r: d / L, g: face point inside
layout(binding = 6) uniform sampler2DArray rl_cell_normal;    // rgb: texture-space normal * 0.5 + 0.5
layout(binding = 7) uniform sampler2DArray rl_cell_color;

uniform int rl_cell_n;      // N
uniform int rl_cell_res;    // texels per face side
uniform int rl_cell_tiles;  // faces per array layer along each side

#include "harness/glsl/search_cost.glsl"

const uint RL_WHITE = 0u, RL_GREY = 1u, RL_BLACK = 2u;

struct RlCellPoint {
  uint state;     // white, grey or black
  vec3 coord;     // grey: the array-texture coordinate of its face point
  float along;    // |q - P'| (cell units)
  float line_length;  // the projection line's length L (cell units)
};

vec3 rl_axis(int a) { return a == 0 ? vec3(1, 0, 0) : (a == 1 ? vec3(0, 1, 0) : vec3(0, 0, 1)); }
vec3 rl_face_normal(int f) { return rl_axis(f / 2) * ((f & 1) == 1 ? 1.0 : -1.0); }

// The projection line through q: its face (an exit face preferring a domain face at edges and
// corners), face point and inner end.
void rl_project(uint cell_bits, vec3 q, out int face, out vec3 on_face, out vec3 inner) {
  uint type = (cell_bits >> 2u) & 3u;
  int axis = int((cell_bits >> 4u) & 7u);
  uint code = (cell_bits >> 7u) & 31u;
  uint domain = (cell_bits >> 12u) & 63u;
  vec3 c = vec3(float(code / 9u), float((code / 3u) % 3u), float(code % 3u)) * 0.5;
  vec3 dir;
  if (type == 0u) {  // perspective from c
    inner = c;
    dir = q - c;
  } else if (type == 1u) {  // axial: the foot on the axis through c along `axis`
    inner = c;
    inner[axis] = q[axis];
    dir = q - inner;
  } else if (type == 2u) {  // planar: the plane through c across `axis`
    inner = q;
    inner[axis] = c[axis];
    dir = rl_axis(axis) * (q[axis] >= c[axis] ? 1.0 : -1.0);
  } else {  // parallel along face `axis`'s outward normal
    inner = q;
    inner[axis / 2] = (axis & 1) == 1 ? 0.0 : 1.0;
    dir = rl_face_normal(axis);
  }
  if (dot(dir, dir) < 1e-12) {
    int f = 0;
    while (f < 5 && ((domain >> uint(f)) & 1u) == 0u) ++f;
    dir = rl_face_normal(f);
  }
  float s = 1e30;
  for (int a = 0; a < 3; ++a)
    if (dir[a] != 0.0) s = min(s, ((dir[a] > 0.0 ? 1.0 : 0.0) - q[a]) / dir[a]);
  s = max(s, 0.0);
  face = -1;
  for (int a = 0; a < 3; ++a) {
    if (dir[a] == 0.0) continue;
    float sa = ((dir[a] > 0.0 ? 1.0 : 0.0) - q[a]) / dir[a];
    if (sa > s + 1e-6) continue;
    int f = 2 * a + (dir[a] > 0.0 ? 1 : 0);
    if (face < 0 || (((domain >> uint(f)) & 1u) == 1u && ((domain >> uint(face)) & 1u) == 0u))
      face = f;
  }
  on_face = clamp(q + dir * s, 0.0, 1.0);
  on_face[face / 2] = float(face & 1);
}

// The array-texture coordinate of face point st on domain face `index`, clamped to the face's
// texel centres (its map does not wrap or bleed into the next tile).
vec3 rl_face_coord(int index, vec2 st) {
  int per_layer = rl_cell_tiles * rl_cell_tiles;
  int tile = index % per_layer;
  float half_texel = 0.5 / float(rl_cell_res);
  st = clamp(st, vec2(half_texel), vec2(1.0 - half_texel));
  vec2 xy = (vec2(float(tile % rl_cell_tiles), float(tile / rl_cell_tiles)) + st) /
            float(rl_cell_tiles);
  return vec3(xy, float(index / per_layer));
}

// Cell lookup and projection of grid point g (one table fetch).
RlCellPoint rl_cell_point(vec3 g) {
  RlCellPoint p;
  p.state = RL_WHITE;
  p.coord = vec3(0.0);
  p.along = 0.0;
  p.line_length = 0.0;
  float n = float(rl_cell_n);
  if (any(lessThan(g, vec3(0.0))) || any(greaterThan(g, vec3(n)))) return p;
  ivec3 cell = min(ivec3(floor(g)), ivec3(rl_cell_n - 1));
  rl_fetches++;
  uvec2 entry = texelFetch(rl_cell_table, cell, 0).xy;
  p.state = entry.x & 3u;
  if (p.state != RL_GREY) return p;
  int face;
  vec3 on_face, inner;
  vec3 q = g - vec3(cell);
  rl_project(entry.x, q, face, on_face, inner);
  uint domain = (entry.x >> 12u) & 63u;
  if (face < 0 || ((domain >> uint(face)) & 1u) == 0u) {
    p.state = RL_WHITE;  // cannot happen for a configured cell (tested on the CPU)
    return p;
  }
  int index = int(entry.y) + bitCount(domain & ((1u << uint(face)) - 1u));
  int a = face / 2;
  vec2 st = vec2(on_face[(a + 1) % 3], on_face[(a + 2) % 3]);
  p.coord = rl_face_coord(index, st);
  p.along = length(on_face - q);
  p.line_length = length(on_face - inner);
  return p;
}

// Inside the encoded surface? 1 inside, 0 outside, -1 white (the ray left the grey region).
int rl_cell_inside(vec3 g) {
  RlCellPoint p = rl_cell_point(g);
  if (p.state == RL_BLACK) return 1;
  if (p.state == RL_WHITE) return -1;
  rl_fetches++;
  vec2 texel = textureLod(rl_cell_distance, p.coord, 0.0).rg;
  bool face_inside = texel.g > 0.5;
  return (face_inside != (p.along > texel.r * p.line_length)) ? 1 : 0;
}

// Slab exit of the ray o + t d (grid units) from the grid [0, N]^3.
float rl_grid_exit(vec3 o, vec3 d) {
  float t = 1e30;
  float n = float(rl_cell_n);
  for (int a = 0; a < 3; ++a) {
    if (d[a] > 0.0) t = min(t, (n - o[a]) / d[a]);
    if (d[a] < 0.0) t = min(t, -o[a] / d[a]);
  }
  return t;
}

// Section 3.5.2: linear search from o along the unit direction d (grid units) for the first
// sample inside the object, stopping where the ray leaves the grey region into a white cell or
// the grid (another front face of the proxy starts the search there); then binary search.
// Returns the hit's t (the last inside sample), or -1; `t_before` is the last outside sample
// (within the final bisection interval), where the attributes are read.
float rl_cell_search(vec3 o, vec3 d, out float t_before) {
  const float step = 1.0 / float(RL_STEPS_PER_CELL);
  float t_end = rl_grid_exit(o, d);
  // Bounded: the longest chord of the grid in steps, plus the first sample.
  int max_steps = int(ceil(1.7320508 * float(rl_cell_n) * float(RL_STEPS_PER_CELL))) + 2;
  float t_out = 0.0;
  float t = 1e-4;
  t_before = 0.0;
  bool found = false;
  for (int i = 0; i < max_steps && t <= t_end; ++i) {
    RL_ITERATE;
    int inside = rl_cell_inside(o + d * t);
#ifndef RL_PROBE
    if (inside < 0 && i > 0) break;
#endif
    if (inside == 1) {
      found = true;
      break;
    }
    t_out = t;
    t += step;
  }
  if (!found) return -1.0;
  float t_in = t;
  for (int i = 0; i < RL_BINARY_STEPS; ++i) {
    RL_ITERATE;
    float mid = 0.5 * (t_out + t_in);
    if (rl_cell_inside(o + d * mid) == 1)
      t_in = mid;
    else
      t_out = mid;
  }
  t_before = t_out;
  return t_in;
}
