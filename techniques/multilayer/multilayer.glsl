// Relief mapping of non-height-field surface details: Policarpo & Oliveira 2006, Section 3.1
// (Algorithms 1 and 2: linear then binary search against all layers in parallel, inside = an
// odd number of layers above the point), Section 3.2 (the interface fix) and Appendix A (the
// layer whose depth is nearest the hit gives normal and colour; back layers' normals point
// down). Layers come in groups of four, one RGBA texel per group: RL_LAYER_GROUPS is 1 (up to
// 4 layers) or 2 (up to 8, the paper's Section 6). Unused layers have depth 1.
#include "harness/glsl/relief_common.glsl"

#define RL_HIT_ATTRIBUTES 1

layout(binding = 4) uniform sampler2DArray rl_layer_depth;  // slice g: layers 4g .. 4g + 3
layout(binding = 5) uniform sampler2DArray rl_layer_nx;     // x of each layer's normal, * 0.5 + 0.5
layout(binding = 6) uniform sampler2DArray rl_layer_ny;     // y, likewise
layout(binding = 7) uniform sampler2DArray rl_layer_color;  // slice l: layer l's colour

// Depths and normals at level 0, or (RL_MIPMAP, Section 6's "regular mip map filtering") from
// their mip chains at the pixel's footprint; colour at level 0 either way.
#ifdef RL_MIPMAP
#define RL_LAYER_FETCH(tex, uvw) RL_FETCH_GRAD(tex, uvw)
#else
#define RL_LAYER_FETCH(tex, uvw) RL_FETCH(tex, uvw)
#endif

// (layers above depth d, layers used) at uv: the parallel comparison of Algorithm 1.
ivec2 rl_layer_counts(vec2 uv, float d) {
  ivec2 c = ivec2(0);
#ifdef RL_IMPOSTOR
  // An impostor is one object in its box, not a tiling: outside it there is nothing (the
  // truth traces the mesh once).
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return c;
#endif
  for (int g = 0; g < RL_LAYER_GROUPS; g++) {
    vec4 layers = RL_LAYER_FETCH(rl_layer_depth, vec3(uv, float(g)));
    c.x += int(dot(vec4(lessThan(layers, vec4(d))), vec4(1.0)));
    c.y += int(dot(vec4(lessThan(layers, vec4(1.0))), vec4(1.0)));
  }
  return c;
}

// The point of the ray p + t s at t. Depth runs with s.z = +1 (down) or -1 (up: an impostor
// seen from behind, Section 4), so t always counts depth units travelled.
RlHit rl_layer_hit(vec3 p, vec3 s, float t, bool hit) {
  RlHit h;
  h.t = t;
  h.uv = p.xy + s.xy * t;
  h.depth = p.z + s.z * t;
  h.layer = -1;
  h.hit = hit;
  return h;
}

// The ray's depth at t: straight (p.z + s.z t), or under the base bent as the fragment's
// quadric (book chapter 5, Eq. 5.3: Vw = s * metric is the world direction per unit t).
float rl_ray_depth(vec3 p, vec3 s, float t, bool bent, vec2 quadric, vec3 metric) {
  if (!bent) return p.z + s.z * t;
  vec3 P = s * metric * t;
  return (P.z - (quadric.x * P.x * P.x + quadric.y * P.y * P.y)) / metric.z;
}

// Algorithms 1 and 2 over t in [0, t_max] along either ray model.
RlHit rl_layer_search(vec3 p, vec3 s, float t_max, bool bent, vec2 quadric, vec3 metric) {
  // Algorithm 1: equal steps; the first sample inside a solid stops it. The inside test does
  // not depend on the direction (impostors seen from behind search upward).
  float size = t_max / float(RL_LINEAR_STEPS);
  float t = 0.0;
  int used_in = 0, used_out = -1;
  bool found = false;
  for (int i = 1; i <= RL_LINEAR_STEPS; i++) {
    RL_ITERATE;
    t = size * float(i);
    ivec2 c = rl_layer_counts(p.xy + s.xy * t, rl_ray_depth(p, s, t, bent, quadric, metric));
    if ((c.x & 1) == 1) {
      used_in = c.y;
      found = true;
      break;
    }
    used_out = c.y;
  }
  // Through every solid: the ray leaves the depth range (a gap, or the silhouette).
  if (!found) {
    RlHit miss = rl_layer_hit(p, s, t, false);
    miss.depth = rl_ray_depth(p, s, t, bent, quadric, metric);
    return miss;
  }
  // Algorithm 2: bisect between the last outside and the first inside sample.
  float lo = t - size, hi = t;
  for (int i = 0; i < RL_BINARY_STEPS; i++) {
    RL_ITERATE;
    float mid = 0.5 * (lo + hi);
    ivec2 c = rl_layer_counts(p.xy + s.xy * mid, rl_ray_depth(p, s, mid, bent, quadric, metric));
    if ((c.x & 1) == 1) {
      hi = mid;
      used_in = c.y;
    } else {
      lo = mid;
      used_out = c.y;
    }
  }
  float best = hi;
#if RL_INTERFACE_FIX
  // Section 3.2: where the last inside and outside samples straddle texels with different
  // layer counts, the one with more layers holds the surface the ray met.
  if (used_out > used_in) best = lo;
#endif
  RlHit h = rl_layer_hit(p, s, best, true);
  h.depth = rl_ray_depth(p, s, best, bent, quadric, metric);
  // Appendix A: the layer nearest in depth is the one hit.
  float nearest = 2.0;
  h.layer = 0;
  for (int g = 0; g < RL_LAYER_GROUPS; g++) {
    vec4 layers = RL_LAYER_FETCH(rl_layer_depth, vec3(h.uv, float(g)));
    for (int k = 0; k < 4; k++) {
      float gap = abs(layers[k] - h.depth);
      if (layers[k] < 1.0 && gap < nearest) {
        nearest = gap;
        h.layer = 4 * g + k;
      }
    }
  }
  return h;
}

// s.z = +1 (down) or -1 (up): to the far side of the depth range.
RlHit rl_intersect(vec3 p, vec3 s) {
#if RL_GRAZING_BIAS && !defined(RL_IMPOSTOR)
  // Appendix A's "depth bias (1-(1-d)*(1-d))": the search vector spans a relief
  // depth * (2 v.z - v.z^2) deep instead of depth, v.z the cosine of the view to the base
  // normal: the full depth seen from above, ever shallower towards grazing views, so the
  // search crosses less texture there (and finds a flattened surface).
  float vz = abs(s.z) / length(vec3(s.xy / rl_depth_aspect, s.z));
  s.xy *= 2.0 * vz - vz * vz;
#endif
  return rl_layer_search(p, s, s.z > 0.0 ? 1.0 - p.z : p.z, false, vec2(0.0), vec3(1.0));
}

// Silhouettes (book chapter 5, Listings 5.5-5.7 with Eq. 5.3, as relief_silhouette): the
// view ray stays straight while the base bends as the fragment's quadric (A, B); t counts
// world units along it, up to where it reaches depth 1 or, on a convex base, returns to the
// top (Listing 5.7). A ray that finds no solid misses: outside the silhouette, or a gap.
RlHit rl_intersect_curved(vec3 p, vec3 s, vec2 quadric, vec3 metric) {
  if (!(s.z > 0.0)) return rl_layer_hit(p, s, 0.0, false);
  vec3 Vw = s * metric;
  float f = (quadric.x * Vw.x * Vw.x + quadric.y * Vw.y * Vw.y) / metric.z;
  float disc = s.z * s.z - 4.0 * f;
  float t_max = 3.0e38;
  if (disc >= 0.0) t_max = 2.0 / (s.z + sqrt(disc));  // depth 1; stable at f = 0
  if (f > 0.0) t_max = min(t_max, s.z / f);           // back to depth 0 (convex base)
  return rl_layer_search(p, s, t_max, true, quadric, metric);
}

// The hit layer's normal (x and y stored, z rebuilt, negative on back layers) and colour. A
// miss that is drawn ends on the floor: a layered map's solid floor faces up in the floor
// colour; a heightfield's floor texel has its own normal and colour.
void rl_hit_attributes(RlHit h, out vec3 tn, out vec3 albedo) {
  if (h.layer < 0) {
    rl_floor_attributes(h.uv, tn, albedo);
    return;
  }
  int g = h.layer / 4, k = h.layer % 4;
  float x = RL_LAYER_FETCH(rl_layer_nx, vec3(h.uv, float(g)))[k] * 2.0 - 1.0;
  float y = RL_LAYER_FETCH(rl_layer_ny, vec3(h.uv, float(g)))[k] * 2.0 - 1.0;
  float z = sqrt(max(0.0, 1.0 - (x * x + y * y)));
  tn = vec3(x, y, (h.layer & 1) == 1 ? -z : z);
  albedo = RL_FETCH(rl_layer_color, vec3(h.uv, float(h.layer))).rgb;
}
