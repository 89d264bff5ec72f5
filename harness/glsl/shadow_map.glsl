// scene_shadows (core/effects.h): whether a world point lies in the shadow of what the light's
// shadow map holds (technique/shadow_map_pass.h) -- the nearest texel's depth, as the light's
// distance along its view axis, against the point's own. Allowed: `rl_shadow_map_bias` world
// units, plus `rl_shadow_map_slope_bias` times how far the surface (normal n) falls across one
// texel of the map (a texel's world width times the tangent of the light's angle to n, capped at
// 20 texels), so that a surface does not shadow itself where the light grazes it. A point outside
// the map's view is lit. The truth decides by a shadow ray (truth/truth_render.cpp).
layout(binding = 12) uniform sampler2D rl_shadow_map;
uniform mat4 rl_light_view_projection;
uniform vec3 rl_light_eye;
uniform vec3 rl_light_forward;  // unit, from the light toward the scene's centre
uniform vec2 rl_light_planes;   // near, far
uniform float rl_shadow_map_bias;
uniform float rl_shadow_map_slope_bias;
uniform float rl_shadow_map_texel;  // a texel's width at unit distance along the light's axis

// A depth-buffer value of the light's perspective view as distance along its axis.
float rl_light_axis_distance(float depth) {
  float n = rl_light_planes.x, f = rl_light_planes.y;
  return 2.0 * n * f / ((f + n) - (2.0 * depth - 1.0) * (f - n));
}

bool rl_in_scene_shadow(vec3 world, vec3 n) {
  vec4 clip = rl_light_view_projection * vec4(world, 1.0);
  if (clip.w <= 0.0) return false;
  vec2 ndc = clip.xy / clip.w;
  if (any(greaterThan(abs(ndc), vec2(1.0)))) return false;
  ivec2 size = textureSize(rl_shadow_map, 0);
  ivec2 texel = clamp(ivec2((0.5 * ndc + 0.5) * vec2(size)), ivec2(0), size - 1);
  float stored = rl_light_axis_distance(texelFetch(rl_shadow_map, texel, 0).r);
  float distance = dot(world - rl_light_eye, rl_light_forward);
  float cos_light = clamp(abs(dot(n, normalize(rl_light_eye - world))), 0.05, 1.0);
  float slope = sqrt(1.0 - cos_light * cos_light) / cos_light;
  float texel_world = rl_shadow_map_texel * distance;
  float bias = rl_shadow_map_bias + rl_shadow_map_slope_bias * texel_world * slope;
  return distance > stored + bias;
}
