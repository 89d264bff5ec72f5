// An object from several heightfields (relief/heightfield_faces.h, the CPU twin): one map per
// cube face, each looking inward, orthographically or with a reverse perspective. A cube point
// (texture space of the cube, u, v, depth in [0, 1]) is inside the object when every face that
// sees it has it behind its surface: the intersection of the faces' solids.
layout(binding = 4) uniform sampler2DArray rl_face_relief;  // rgb: normal (face u, v, up), a: depth
layout(binding = 5) uniform sampler2DArray rl_face_color;

uniform int rl_face_count;
uniform mat3 rl_face_from_cube[6];  // rows: a face's u, v and inward axes in the cube
uniform float rl_face_cop;          // reverse perspective's centre of projection (> 1), or 0
uniform float rl_face_texel;        // one texel of the faces' maps (1 / resolution)

// As deep as an empty column (a bake ray that missed stores 1): kEmptyFaceDepth.
const float RL_FACE_EMPTY = 1.0 - 0.5 / 255.0;
// Slack of the inside test, in depth units: half an 8-bit step, so a point exactly on a stored
// depth counts as inside whatever the rounding.
const float RL_FACE_SLACK = 0.5 / 255.0;

#include "harness/glsl/search_cost.glsl"

// Cube point -> face k's texture space (ReverseProjection::texture_from_affine).
vec3 rl_face_texture(int k, vec3 c) {
  vec3 a = rl_face_from_cube[k] * (c - 0.5) + 0.5;
  if (rl_face_cop <= 1.0) return a;
  float s = rl_face_cop / (rl_face_cop - a.z);
  return vec3(0.5 + (a.xy - 0.5) * s, a.z * (rl_face_cop - 1.0) / (rl_face_cop - a.z));
}

// How far c lies behind face k's surface (>= 0: inside that face's solid); a large positive
// value where the face does not see c, a negative one over an empty column. `facing`: the
// stored normal's component towards the face (1 where the face sees the surface head-on).
float rl_face_behind(int k, vec3 c, out float facing) {
  facing = -1.0;
  vec3 t = rl_face_texture(k, c);
  if (any(lessThan(t.xy, vec2(0.0))) || any(greaterThan(t.xy, vec2(1.0)))) return 1e9;
  ++rl_fetches;
  vec4 r = textureLod(rl_face_relief, vec3(t.xy, float(k)), 0.0);
  facing = r.b * 2.0 - 1.0;
  return r.a >= RL_FACE_EMPTY ? -1.0 : t.z - r.a;
}

// Inside every face's solid? Faces are asked in order and the first that says no ends the test
// (its fetch is the last). When inside, `surface` is the face that shades the point: of the
// faces it lies within a texel of (the surface is there), the one that sees the surface most
// head-on -- a face seeing it at a grazing angle has a steep, bilinear-blurred normal there.
bool rl_faces_inside(vec3 c, out int surface) {
  float behind[6], facing[6];
  float nearest = 1e30;
  surface = 0;
  for (int k = 0; k < rl_face_count; ++k) {
    behind[k] = rl_face_behind(k, c, facing[k]);
    if (behind[k] < -RL_FACE_SLACK) return false;
    nearest = min(nearest, behind[k]);
  }
  float best = -2.0;
  for (int k = 0; k < rl_face_count; ++k)
    if (behind[k] <= nearest + rl_face_texel && facing[k] > best) {
      best = facing[k];
      surface = k;
    }
  return true;
}

// Face k's normal and colour at cube point c: the normal in the cube's texture space.
void rl_face_attributes(int k, vec3 c, out vec3 normal, out vec3 albedo) {
  vec3 t = rl_face_texture(k, c);
  vec3 coord = vec3(clamp(t.xy, 0.0, 1.0), float(k));
  rl_fetches += 2;
  vec3 s = textureLod(rl_face_relief, coord, 0.0).rgb * 2.0 - 1.0;
  normal = transpose(rl_face_from_cube[k]) * vec3(s.xy, -s.z);
  albedo = textureLod(rl_face_color, coord, 0.0).rgb;
}
