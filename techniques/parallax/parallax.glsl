// Parallax (offset) mapping, Kaneko et al. 2001; book chapter 5, Listing 5.1.
// One depth fetch at the fragment's uv, then the uv is shifted along the view direction by
// that depth. With RL_OFFSET_LIMITING the shift is d * view.xy on the *unit* tangent-space
// view vector, as Listing 5.1 does (no division by view.z), which bounds the offset at
// grazing angles; without it, the shift reaches the view ray at depth d (Kaneko's form).
#include "harness/glsl/relief_common.glsl"

RlHit rl_intersect(vec3 p, vec3 s) {
  float d = rl_relief_depth(p.xy) - RL_PARALLAX_BIAS;
  vec2 offset = s.xy * d;
#if RL_OFFSET_LIMITING
  // Unit tangent-space view z from the texture-space step s (s.z = 1 depth unit).
  vec2 world_xy = s.xy / rl_depth_aspect;
  float view_z = inversesqrt(1.0 + dot(world_xy, world_xy));
  offset *= view_z;
#endif
  RlHit h;
  h.uv = p.xy + offset;
  // Parallax claims the relief surface at the shifted uv; the depth there comes with the
  // shading fetch, so it costs no extra fetch in a real shader. Here it is an extra counted
  // fetch only in ray-probe mode, where no shading fetch follows.
#ifdef RL_PROBE
  h.depth = rl_relief_depth(h.uv);
#else
  h.depth = textureLod(rl_relief, h.uv, 0.0).a;
#endif
  h.t = h.depth - p.z;
  h.layer = 0;
  h.hit = true;
  return h;
}
