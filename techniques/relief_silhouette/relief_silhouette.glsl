// Relief mapping with curvature silhouettes: book chapter 5, "Silhouette edges and Relief
// Texture mapping", Listings 5.5-5.7, Equations 5.1-5.3 (Oliveira & Policarpo 2005).
//
// Around the fragment the base is the quadric z = A x^2 + B y^2 (Eq. 5.1, tangent coordinates
// in world units, z pointing into the surface, (A, B) the vertex curvature interpolated). The
// view ray stays straight in world space; its depth under the bent base at parameter t is
// measured vertically (Eq. 5.3, the chapter's approximation) or along U, the unit vector
// perpendicular to the ray in the plane of the ray and the normal (Eq. 5.2, the "exact"
// distance, with the discriminant test falling back to Eq. 5.3). The linear + binary search of
// Listing 5.6 runs over [0, t_max], t_max from Listing 5.7: where the approximate depth first
// reaches 1, or returns to 0 on a convex base. No sample inside: the ray left the relief
// volume, a miss (the surface pass discards it: the silhouette).
#include "harness/glsl/relief_common.glsl"

// Depth (texture units) of the ray point P = Vw t under the quadric; u_dir is U, a_u the
// quadric's a coefficient along U (both constant per ray).
float rl_bent_depth(vec3 P, vec2 quadric, vec3 u_dir, float a_u, float depth_scale) {
  float d_approx = P.z - (quadric.x * P.x * P.x + quadric.y * P.y * P.y);  // Eq. 5.3
#if RL_QUADRIC_EXACT
  // Eq. 5.2: R = P + U s on the quadric; a s^2 + b s + c = 0 with c = -d_approx. Inside (c < 0)
  // its positive root, written without cancellation; outside, any negative depth will do. The
  // substitution gives b its -U.z; the chapter prints b without it (RL_EQ52_AS_PRINTED).
#if RL_EQ52_AS_PRINTED
  float b = 2.0 * (quadric.x * P.x * u_dir.x + quadric.y * P.y * u_dir.y);
#else
  float b = 2.0 * (quadric.x * P.x * u_dir.x + quadric.y * P.y * u_dir.y) - u_dir.z;
#endif
  float c = -d_approx;
  float disc = b * b - 4.0 * a_u * c;
  float q = b + sqrt(max(disc, 0.0));
  if (c < 0.0 && disc >= 0.0 && q > 1e-20) return (-2.0 * c / q) / depth_scale;
#endif
  return d_approx / depth_scale;
}

// p: start (u, v, depth 0); s: ray direction in texture units per unit t; quadric (A, B) in
// world units; metric: world length of one unit of u, of v, and of depth.
RlHit rl_intersect_curved(vec3 p, vec3 s, vec2 quadric, vec3 metric) {
  RlHit miss = rl_hit_on_ray(p, s, 0.0, false);
  if (!(s.z > 0.0)) return miss;
  vec3 Vw = s * metric;  // world tangent-space direction per unit t
  // Listing 5.7: approximate depth(t) = s.z t - f t^2.
  float f = (quadric.x * Vw.x * Vw.x + quadric.y * Vw.y * Vw.y) / metric.z;
  float disc = s.z * s.z - 4.0 * f;
#if RL_PLANE_T_MAX
  float t_max = 1.0 / s.z;  // the tangent plane's depth 1, whatever the curvature
#else
  float t_max = 3.0e38;
  if (disc >= 0.0) t_max = 2.0 / (s.z + sqrt(disc));  // depth 1; stable at f = 0
  if (f > 0.0) t_max = min(t_max, s.z / f);           // back to depth 0 (convex base)
#endif
  // U: perpendicular to the ray, in its plane with the normal, pointing out of the surface.
  vec3 v_unit = normalize(Vw);
  vec3 u_dir = vec3(0.0, 0.0, -1.0) + v_unit * v_unit.z;
  float lu = length(u_dir);
  u_dir = lu > 1e-6 ? u_dir / lu : vec3(0.0, 0.0, -1.0);  // ray along the normal: U undefined
  float a_u = quadric.x * u_dir.x * u_dir.x + quadric.y * u_dir.y * u_dir.y;

  const int linear_steps = RL_LINEAR_STEPS;
  const int binary_steps = RL_BINARY_STEPS;
  float size = t_max / float(linear_steps);
  float t = 0.0;
  float best = -1.0;
  for (int i = 0; i < linear_steps; i++) {
    RL_ITERATE;
    t += size;
    if (rl_bent_depth(Vw * t, quadric, u_dir, a_u, metric.z) >=
        rl_relief_depth(p.xy + s.xy * t)) {
      best = t;
      break;
    }
  }
  if (best < 0.0) return miss;  // left the relief volume: outside the silhouette
  t = best - size;              // last outside sample; refine between it and the first inside
  for (int i = 0; i < binary_steps; i++) {
    RL_ITERATE;
    size *= 0.5;
    if (rl_bent_depth(Vw * (t + size), quadric, u_dir, a_u, metric.z) >=
        rl_relief_depth(p.xy + s.xy * (t + size)))
      best = t + size;
    else
      t += size;
  }
  RlHit h = rl_hit_on_ray(p, s, best, true);
  h.depth = rl_bent_depth(Vw * best, quadric, u_dir, a_u, metric.z);
  return h;
}

// The planar entry point (probe mode, and scenes that do not ask for silhouettes): the same
// search on the quadric of the probe ray, or on the flat tangent plane. Probe rays give the
// quadric in texture units (metric 1).
RlHit rl_intersect(vec3 p, vec3 s) {
#ifdef RL_PROBE
  return rl_intersect_curved(p, s, rl_probe_quadric, vec3(1.0));
#else
  return rl_intersect_curved(p, s, vec2(0.0), vec3(1.0));
#endif
}
