// Texture-space AO map on the GPU (Limberger et al., Section IV-A: "performed off-line using a
// GLSL shader"): one fragment per texel, the same horizon search and polygon area as the CPU's
// relief/ao_map.cpp (compute_ao_map_march), in float. The low-pass filter runs afterwards on the CPU.
layout(binding = 0) uniform sampler2D rl_heights;  // r: height in texel units, top = highest
uniform int rl_directions;
uniform int rl_max_steps;
uniform float rl_highest;  // the map's highest point: the search's early stop

layout(location = 0) out vec4 o_visibility;

// Wraps like GL_REPEAT. Not with %: GLSL leaves it undefined for negative operands (llvmpipe
// got non-power-of-two sizes wrong that way).
float rl_height_at(ivec2 p) {
  ivec2 size = textureSize(rl_heights, 0);
  return texelFetch(rl_heights, p - size * ivec2(floor(vec2(p) / vec2(size))), 0).r;
}

// Bilinear at texel coordinates (texel centre i at i), wrapping: exact weights, not the
// sampler's fixed-point ones.
float rl_height_sample(vec2 q) {
  vec2 f = floor(q);
  ivec2 i = ivec2(f);
  vec2 a = q - f;
  float top = mix(rl_height_at(i), rl_height_at(i + ivec2(1, 0)), a.x);
  float bottom = mix(rl_height_at(i + ivec2(0, 1)), rl_height_at(i + ivec2(1, 1)), a.x);
  return mix(top, bottom, a.y);
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float h0 = rl_height_at(p);
  float area = 0.0, first = 0.0, previous = 0.0;
  for (int j = 0; j < rl_directions; ++j) {
    float phi = 6.283185307179586 * float(j) / float(rl_directions);
    vec2 d = vec2(cos(phi), sin(phi));
    float best = 0.0;  // tan of the horizon elevation
    for (int k = 1; k <= rl_max_steps; ++k) {
      if (rl_highest - h0 <= best * float(k)) break;
      float rise = rl_height_sample(vec2(p) + d * float(k)) - h0;
      best = max(best, rise / float(k));
    }
    // Exactly 1 for an open direction, as on the CPU: inversesqrt may be approximate, and the
    // low-pass filter treats anything below 1 as occluded.
    float q = 1.0 + best * best;
    float r = q == 1.0 ? 1.0 : inversesqrt(q);
    if (j == 0) first = r; else area += previous * r;
    previous = r;
  }
  area += previous * first;
  o_visibility = vec4(min(1.0, area / float(rl_directions)), 0.0, 0.0, 1.0);
}
