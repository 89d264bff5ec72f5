// An object from several heightfields, ray cast (Baboud & Decoret 2006, Section 4.2): per
// fragment of the cube's front faces, the view ray's chord through the cube is searched
// linearly for the first point inside every face's solid (harness/glsl/heightfield_faces.glsl),
// then refined by bisection; the face whose surface the hit lies on shades it. With RL_PROBE, a
// ray-probe pass instead: one ray per fragment from textures, in the cube's texture space.
#include "harness/glsl/heightfield_faces.glsl"

// Exit of the ray o + t d (o in the cube) from the unit cube.
float rl_cube_exit(vec3 o, vec3 d) {
  vec3 safe = mix(d, vec3(1e-9), lessThan(abs(d), vec3(1e-9)));
  vec3 far = max((vec3(0.0) - o) / safe, (vec3(1.0) - o) / safe);
  return max(0.0, min(min(far.x, far.y), far.z));
}

// The first point of o + t d, t in [0, t_end], inside the object: `t` and its face; false when
// the chord misses it. RL_LINEAR_STEPS samples over the chord (the entry included), then
// RL_BINARY_STEPS bisections between the last outside and the first inside sample.
bool rl_object_search(vec3 o, vec3 d, float t_end, out float t, out int surface) {
  t = 0.0;
  surface = 0;
  float dt = t_end / float(RL_LINEAR_STEPS);
  float t_out = 0.0;
  bool found = false;
  for (int i = 0; i <= RL_LINEAR_STEPS; ++i) {
    RL_ITERATE;
    float ti = dt * float(i);
    int s;
    if (rl_faces_inside(o + d * ti, s)) {
      t = ti;
      surface = s;
      found = true;
      break;
    }
    t_out = ti;
  }
  if (!found) return false;
  if (t == 0.0) return true;  // the object touches the cube's face here
  for (int i = 0; i < RL_BINARY_STEPS; ++i) {
    RL_ITERATE;
    float mid = 0.5 * (t_out + t);
    int s;
    if (rl_faces_inside(o + d * mid, s)) {
      t = mid;
      surface = s;
    } else {
      t_out = mid;
    }
  }
  return true;
}

#ifdef RL_PROBE
#include "harness/glsl/probe_io.glsl"

// A probe ray starts inside the cube (or on it) and runs to its exit; t in its own units. The
// layer reported is the face that shades the hit.
void main() {
  vec4 origin_q, direction_q;
  rl_probe_ray(origin_q, direction_q);
  vec3 origin = origin_q.xyz, direction = direction_q.xyz;
  float len = length(direction);
  vec3 d = direction / max(len, 1e-20);
  float t;
  int surface;
  bool hit = len > 0.0 && rl_object_search(origin, d, rl_cube_exit(origin, d), t, surface);
  vec3 p = origin + d * t;
  rl_probe_write(hit ? t / len : 0.0, p.xy, p.z, float(surface), hit, rl_fetches);
}
#else
#include "harness/glsl/shading.glsl"

in vec3 v_tex;

uniform vec3 rl_eye;
uniform vec3 rl_light;
uniform vec3 rl_eye_texture;
uniform mat4 rl_view_projection;
uniform mat4 rl_world_from_texture;
uniform mat3 rl_normal_from_texture;

#include "harness/glsl/gbuffer_outputs.glsl"

void main() {
  vec3 d = normalize(v_tex - rl_eye_texture);
  float t;
  int surface;
  if (!rl_object_search(v_tex, d, rl_cube_exit(v_tex, d), t, surface)) RL_DISCARD;
  vec3 hit_tex = v_tex + d * t;
  vec3 hit_world = (rl_world_from_texture * vec4(hit_tex, 1.0)).xyz;
  vec4 hit_clip = rl_view_projection * vec4(hit_world, 1.0);
  gl_FragDepth = clamp(0.5 * hit_clip.z / hit_clip.w + 0.5, 0.0, 1.0);

  vec3 tn, albedo;
  rl_face_attributes(surface, hit_tex, tn, albedo);
  vec3 V = normalize(hit_world - rl_eye);
  vec3 nw = rl_normal_from_texture * tn;
  nw = dot(nw, nw) > 0.0 ? normalize(nw) : -V;
  if (dot(nw, V) > 0.0) nw = -nw;  // facing the viewer, as the truth's mesh normals
  vec3 to_light = normalize(rl_light - hit_world);
  o_color = vec4(rl_shade(albedo, nw, to_light, -V, false), 1.0);
#ifdef RL_GBUFFER
  o_position = vec4(hit_world, 1.0);
  o_normal = vec4(nw, 0.0);
  o_hit = vec4(hit_tex.xy, float(surface), float(rl_fetches));
  o_aux = vec4(1.0, 0.0, dot(rl_ambient * albedo, vec3(1.0 / 3.0)), 0.0);
#endif
  rl_count_fragment();
}
#endif
