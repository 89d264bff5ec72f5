// Texture-space ambient occlusion (Limberger, Schetinger & Oliveira, Section IV): the AO map
// (harness/relief/ao_map.h) read at the hit, updated for a rescaled relief depth by Eq. 6.
// Compiled in only when the scene asks for ambient_occlusion.

layout(binding = 8) uniform sampler2D rl_ao;  // r: visibility at the depth the map was made for
// s = the scene's depth / the depth the map was computed for; 1 needs no update.
uniform float rl_ao_rescale;

// Eq. 6 (relief/ao_map.cpp, ao_rescaled(), is the same formula): the visible cone taken as a
// circle of radius r = sqrt(ao) (Eq. 4), its rim raised to s H, H^2 = 1 - r^2 (Eq. 5).
float rl_ao_rescaled(float ao, float s) {
  ao = clamp(ao, 0.0, 1.0);
  float r2_prime = s * s * (1.0 - ao) + ao;
  if (!(r2_prime > 0.0)) return 1.0;  // s = 0 and ao = 0: a flat relief
  return clamp(ao / r2_prime, 0.0, 1.0);
}

#if defined(RL_META_AO_PRODUCT) || defined(RL_META_AO_MIN)
// A meta-relief combined per fetch: each layer's AO map read at its own tiling and combined by
// product or minimum (Section IV-A; relief/meta_relief.cpp, combine_ao_maps(), the same), so a
// fractional tiling stays seamless beyond the first base tile.
layout(binding = 18) uniform sampler2D rl_meta_ao[RL_META_LAYERS];

float rl_stored_ao(vec2 uv) {
  float ao = 1.0;
  for (int i = 0; i < RL_META_LAYERS; ++i) {
    float a = clamp(RL_FETCH(rl_meta_ao[i], uv * rl_meta_tiling[i]).r, 0.0, 1.0);
#ifdef RL_META_AO_MIN
    ao = min(ao, a);
#else
    ao *= a;
#endif
  }
  return ao;
}
#elif defined(RL_AO_PACKED)
// The AO of the texel the shading just read for the hit's normal (relief_common.glsl).
float rl_stored_ao(vec2 uv) { return rl_packed_ao; }
#else
float rl_stored_ao(vec2 uv) { return RL_FETCH(rl_ao, uv).r; }
#endif

float rl_ambient_occlusion(vec2 uv) {
  float ao = rl_stored_ao(uv);
#ifdef RL_AO_EQ6
  ao = rl_ao_rescaled(ao, rl_ao_rescale);
#endif
  return ao;
}
