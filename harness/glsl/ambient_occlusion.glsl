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

float rl_ambient_occlusion(vec2 uv) {
  float ao = RL_FETCH(rl_ao, uv).r;
#ifdef RL_AO_EQ6
  ao = rl_ao_rescaled(ao, rl_ao_rescale);
#endif
  return ao;
}
