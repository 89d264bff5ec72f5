// Blinn-Phong with the shadow of Listing 5.3 (colour scaled, no specular). The truth
// (harness/truth/truth.cpp, shade()) evaluates the same formula in double precision.
uniform vec3 rl_ambient;
uniform vec3 rl_diffuse;
uniform vec3 rl_specular;
uniform float rl_shininess;
uniform float rl_shadow_intensity;
// Visibility of the ambient light at the shaded point: the AO map's value where the scene asks
// for ambient_occlusion, else 1 (set before rl_shade).
float rl_ambient_visibility = 1.0;

vec3 rl_shade(vec3 albedo, vec3 n, vec3 to_light, vec3 to_eye, bool in_shadow) {
  float diff = max(dot(n, to_light), 0.0);
  float spec = pow(max(dot(n, normalize(to_light + to_eye)), 0.0), rl_shininess);
  vec3 lit = in_shadow ? albedo * rl_diffuse * diff * rl_shadow_intensity
                       : albedo * rl_diffuse * diff + rl_specular * spec;
  return rl_ambient_visibility * rl_ambient * albedo + lit;
}
