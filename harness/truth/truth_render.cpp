#include "truth/truth_render.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/columns.h"
#include "core/elapsed.h"
#include "core/hash.h"
#include "core/parallel.h"
#include "core/ray_box.h"
#include "core/sharded_counter.h"
#include "truth/ao_truth_cache.h"
#include "truth/displaced_truth.h"
#include "truth/objects_truth.h"
#include "truth/pattern_base_truth.h"
#include "truth/reference_ao.h"

namespace rl {
namespace {

// The truth's columns (the sweep writes them from the trace and the asset's truth).
const ColumnDeclaration truth_columns(
    "truth",
    {ColumnSpec{"truth_subdivision", "",
                "the truth's Embree front end: k x k per texel of a heightfield's lifted "
                "grid, n x n per base triangle of a curved base's sheet (speed, not accuracy)"}
         .neither_better(),
     ColumnSpec{
         "truth_bound", "depth units",
         "the truth's vertical deviation from the surface it stands for (0 for the exact truths)"}
         .neither_better(),
     {"truth_flagged", "",
      "truth_uncertain_pct above 0.1 %: wrong_pct could be the truth's own error, not scored",
      ColumnKind::Flag},
     ColumnSpec{"truth_ms", "ms", "time to trace the truth of this view (shared by its cells)"}
         .neither_better(),
     ColumnSpec{"truth_unresolved_px", "pixels",
                "covered pixels whose truth ray found no surface (0)"}
         .neither_better(),
     {"beyond_quad_pct", "% of the object's pixels",
      "a relief impostor: of the pixels the object covers at this view (scene objects in front "
      "of it aside), the share its quad's footprint misses -- what no render of the quad can "
      "show, and what wrong_pct (over the quad's pixels) leaves out"},
     ColumnSpec{"truth_ao_rays", "rays",
                "hemisphere rays the reference AO of this view traced (cached pixels counted too)"}
         .neither_better(),
     {"truth", "", "the truth level (source, sampled, model; @N: the map at another resolution)",
      ColumnKind::Text}});

}  // namespace

namespace {

constexpr double kAboveTop = 1e-6;  // depth units above the top plane where truth rays start
constexpr double kFloor = 1e-4;     // depth units within which a hit counts as on the floor

// What a truth render counts besides its rays, from every core.
struct TruthCounters {
  ShardedCounter ao_rays;             // hemisphere directions sampled
  ShardedCounter ao_traced;           // those traced (the truth counts them as shadow rays)
  ShardedCounter object_shadow_rays;  // scene_shadows' rays against the objects
  // scene_shadows' rays from objects against a world-space relief: traced as first hits (the
  // truth counts them as primary rays), counted as shadow rays.
  ShardedCounter relief_rays_from_objects;
  std::atomic<long> unresolved{0};
  std::atomic<long> beyond_quad{0};  // TruthStats::beyond_quad
};

// The ray o + t d against the texture-space box [0, tile]^2 x [0, 1].
bool clip_to_box(const glm::dvec3& o, const glm::dvec3& d, double tile, double& t_in,
                 double& t_out) {
  return clip_ray_to_box(o, d, glm::dvec3(0), glm::dvec3(tile, tile, 1), t_in, t_out);
}

// Whether the ray o + t d meets the object anywhere in its box: for an impostor's ray that
// misses the quad, whether the object lies in that pixel all the same.
bool meets_object_in_box(const TruthSurface& truth, const glm::dvec3& o, const glm::dvec3& d,
                         double tile) {
  double t_in = 0, t_out = 0;
  if (!clip_to_box(o, d, tile, t_in, t_out)) return false;
  return truth.intersect(o + d * t_in, d, 0.0, t_out - t_in).hit;
}

// The first surface point along the camera ray o + t d (texture space, t = world distance)
// for the scene's proxy; false when the pixel shows background. On return the hit is at
// t = t_start + h.t.

bool trace_primary(const TruthSurface& truth, const ReliefMap& map, const SceneDesc& scene,
                   const glm::dvec3& o, const glm::dvec3& d, double bottom, double& t_start,
                   TruthHit& h, TruthCounters& counters) {
  if (scene.impostor()) {
    // The quad through the object's middle, seen from either side: the ray is searched over
    // the whole depth range where it crosses the quad's footprint.
    const double t_quad = d.z == 0 ? -1 : (0.5 - o.z) / d.z;
    const glm::dvec3 at = o + d * t_quad;
    if (t_quad <= 0 || at.x < 0 || at.y < 0 || at.x > scene.tile || at.y > scene.tile) {
      if (meets_object_in_box(truth, o, d, scene.tile)) ++counters.beyond_quad;
      return false;
    }
    const double t0 = (0.0 - o.z) / d.z, t1 = (1.0 - o.z) / d.z;
    t_start = std::min(t0, t1);
    h = truth.intersect(o + d * t_start, d, 0.0, std::max(t0, t1) - t_start);
    return h.hit;
  }
  if (scene.in_cube()) {
    // A closed mesh in its cube, seen from anywhere: the first surface inside the cube.
    double t_in = 0, t_out = 0;
    if (!clip_to_box(o, d, 1.0, t_in, t_out)) return false;
    t_start = t_in;
    h = truth.intersect(o + d * t_in, d, 0.0, t_out - t_in);
    return h.hit;
  }
  if (d.z <= 0) return false;  // never descends into the relief
  if (scene.proxy == Proxy::Box) {
    // The solid under the heightfield, clipped to the box [0, tile]^2 x [0, 1].
    double t_in = 0, t_out = 0;
    if (!clip_to_box(o, d, scene.tile, t_in, t_out)) return false;
    const glm::dvec3 entry = o + d * t_in;
    if (entry.z > kAboveTop && entry.z >= map.surface_depth(entry.x, entry.y)) {
      t_start = t_in;  // entered through a side below the surface: the box's wall
      h.hit = true;
      h.t = 0;
      h.point = entry;
      return true;
    }
    t_start = t_in - kAboveTop / d.z;
    h = truth.intersect(o + d * t_start, d, 0.0, t_out - t_start);
    const glm::dvec3 exit = o + d * t_out;
    const bool through_floor = exit.z >= 1.0 - kFloor;
    if (h.hit && h.point.z >= 1.0 - kFloor) h.hit = false;  // on the floor: decided below
    if (h.hit) return true;
    if (!through_floor || scene.empty_floor) return false;  // left the box: background
    // A solid floor: the ray meets it where it leaves through the bottom.
    h.hit = true;
    h.has_normal = false;
    h.t = t_out - t_start;
    h.point = exit;
    return true;
  }
  const double t_top = -o.z / d.z;
  const glm::dvec3 entry = o + d * t_top;
  if (t_top <= 0 || entry.x < 0 || entry.y < 0 || entry.x > scene.tile || entry.y > scene.tile)
    return false;  // misses the base: background
  // Start a hair above the top plane: a ray starting exactly on a flat top (depth 0) would
  // miss it at t = 0 and continue inside the solid.
  t_start = t_top - kAboveTop / d.z;
  const glm::dvec3 start = o + d * t_start;
  const double t_bottom = (bottom - start.z) / d.z;
  h = truth.intersect(start, d, 0.0, t_bottom);
  if (!h.hit && scene.empty_floor) return false;  // through a pattern's gaps: background
  if (!h.hit && !map.layers.empty()) {
    // Through a pattern's gaps onto its solid floor (depth 1).
    h.t = (1.0 - start.z) / d.z;
    h.point = start + d * h.t;
    return true;
  }
  if (!h.hit) {
    // Rounding let the ray through the floor; it is inside the relief there.
    ++counters.unresolved;
    h.point = start + d * t_bottom;
    h.t = t_bottom;
  }
  return true;
}

}  // namespace

glm::dvec3 shade(const Material& m, const glm::dvec3& albedo, const glm::dvec3& n,
                 const glm::dvec3& to_light, const glm::dvec3& to_eye, bool in_shadow,
                 double ambient_visibility) {
  const double diff = std::max(glm::dot(n, to_light), 0.0);
  const double spec =
      std::pow(std::max(glm::dot(n, glm::normalize(to_light + to_eye)), 0.0), m.shininess);
  const glm::dvec3 lit = in_shadow ? albedo * m.diffuse * diff * m.shadow_intensity
                                   : albedo * m.diffuse * diff + m.specular * spec;
  return ambient_visibility * m.ambient * albedo + lit;
}

double truth_hit_bound(double vertical, double rounding, const glm::dvec3& base_normal,
                       const glm::dvec3& geometric_normal, const glm::dvec3& shading_normal,
                       const glm::dvec3& dir, const glm::dvec3& position) {
  // Cosines floored so a ray exactly tangent to the surface states a huge bound, not infinity.
  const double across_surface = std::max(std::abs(glm::dot(geometric_normal, dir)), 1e-9);
  const double across_shading = std::max(std::abs(glm::dot(shading_normal, dir)), 1e-9);
  const double largest =
      std::max({std::abs(position.x), std::abs(position.y), std::abs(position.z)});
  return vertical * std::abs(glm::dot(geometric_normal, base_normal)) / across_surface +
         rounding / across_shading + std::sqrt(3.0) * 0x1p-24 * largest;
}

namespace {

void write_relief_pixel(GBuffer& g, size_t i, const SceneDesc& scene, const glm::dvec3& albedo,
                        const glm::dvec3& n, const glm::dvec3& world, const glm::dvec3& to_light,
                        const glm::dvec3& dir, const glm::dvec2& uv, bool in_shadow,
                        const AoEstimate& ao, double bound) {
  const glm::dvec3 c = shade(scene.material, albedo, n, to_light, -dir, in_shadow, ao.visibility);
  g.color[i] = glm::vec4(glm::vec3(c), 1.0f);
  g.position[i] = glm::vec4(glm::vec3(world), 1.0f);
  g.normal[i] = glm::vec4(glm::vec3(n), in_shadow ? 1.0f : 0.0f);
  g.hit[i] = glm::vec4(float(uv.x), float(uv.y), 0.0f, 0.0f);
  const glm::dvec3 ambient = scene.material.ambient * albedo;
  g.aux[i] = glm::vec4(float(ao.visibility), float(ao.std_error),
                       float((ambient.x + ambient.y + ambient.z) / 3.0), float(bound));
}

// Per-pixel seed of the reference AO's directions: the same on every run and thread count.
uint64_t ao_seed(size_t pixel) {
  return fnv1a64(&pixel, sizeof pixel, 0x5eed0a0ull);
}

// The reference AO at pixel `i`: `trace()`, or an earlier run's estimate where the cache has
// one for exactly this hit (truth/ao_truth_cache.h).
template <typename Trace>
AoEstimate reference_ao_at(AoTruthCache* cache, size_t i, const glm::dvec3& point,
                           const glm::dvec3& normal, Trace&& trace) {
  return cache ? cache->estimate(i, point, normal, trace) : trace();
}

// A planar truth hit's shading normal and albedo, as the shaders shade it.
struct Surface {
  glm::dvec3 normal, albedo;
};

Surface planar_surface(const PlanarBase& base, const ReliefMap& map, const TruthHit& h,
                       const glm::dvec2& uv, const glm::dvec3& dir) {
  // A tangent-space normal in the base's unit frame.
  auto in_base_frame = [&](const glm::dvec3& t) {
    return glm::normalize(t.x * glm::normalize(base.dpdu()) + t.y * glm::normalize(base.dpdv()) +
                          t.z * base.normal());
  };
  glm::dvec3 n = in_base_frame(decode_normal(map.surface_relief(uv.x, uv.y)));
  if (h.tangent_normal) {
    n = in_base_frame(h.normal);
  } else if (h.has_normal) {
    // The surface's own normal (mesh truth), from texture space (u, v, depth) to world by the
    // inverse transpose of the base's scaling; facing the viewer.
    const glm::dvec3 m = h.normal;
    n = glm::normalize(glm::dvec3(m.x / glm::length(base.dpdu()), m.y / glm::length(base.dpdv()),
                                  -m.z / base.depth));
    if (glm::dot(n, dir) > 0) n = -n;
  }
  const glm::dvec3 albedo = h.has_albedo ? h.albedo : glm::dvec3(map.sample_color(uv.x, uv.y));
  // The solid floor under a multilayer map: facing up, in the floor colour.
  if (!map.layers.empty() && !h.hit) return {base.normal(), glm::dvec3(map.floor_color)};
  return {n, albedo};
}

// Whether a planar truth hit is in its own shadow, as the shaders decide it.
bool planar_in_shadow(const TruthSurface& truth, const PlanarBase& base, const SceneDesc& scene,
                      const TruthHit& h, const glm::dvec3& world) {
  const glm::dvec3 l = base.texture_direction(scene.light_position - world);
  const double t_start = 1e-4 / std::max(1.0, glm::length(l));
  if (scene.impostor()) {
    // Lit from either side: toward the light until the ray leaves the depth range.
    const double t_exit = l.z < 0 ? -h.point.z / l.z : (l.z > 0 ? (1.0 - h.point.z) / l.z : 1e9);
    return t_exit > t_start && truth.occluded(h.point, l, t_start, t_exit);
  }
  if (l.z >= 0) return true;  // light at or below the hit (as the shaders decide)
  // From the hit toward the light, up to where it leaves the relief at the top.
  return truth.occluded(h.point, l, t_start, std::min(1.0, -h.point.z / l.z));
}

// scene_shadows' shadow ray from world point `p`: toward the light, starting off the surface p
// lies on and ending short of the light; none (length 0) where the light is that close.
struct WayToLight {
  glm::dvec3 origin{0}, direction{0};
  double length = 0;
};
WayToLight way_to_light(const SceneDesc& scene, const glm::dvec3& p) {
  const glm::dvec3 to_light = scene.light_position - p;
  const double reach = glm::length(to_light), start = 1e-4 * scene.size;
  if (!(reach > 2 * start)) return {};
  const glm::dvec3 dir = to_light / reach;
  return {p + dir * start, dir, reach - 2 * start};
}

// scene_shadows: whether the way from world point `p` to the light meets a scene object.
bool objects_block_light(const ObjectsTruth* objects, const SceneDesc& scene, const glm::dvec3& p,
                         TruthCounters& counters) {
  if (!objects || objects->empty()) return false;
  const WayToLight way = way_to_light(scene, p);
  if (way.length <= 0) return false;
  ++counters.object_shadow_rays;
  return objects->intersect(way.origin, way.direction, way.length).hit;
}

// scene_shadows: whether the planar relief blocks the light's way to world point `p` (an
// object's, or the relief's own) as the light sees it -- through its quad, as every eye does:
// the light's ray toward p enters the relief's depth range through the quad's top and meets
// the surface before p (the shadow map holds exactly that; light that would come in through
// the depth range's sides, under the quad's edge, meets no relief, as no eye sees any there).
bool relief_blocks_light(const TruthSurface& truth, const PlanarBase& base, const SceneDesc& scene,
                         double bottom, const glm::dvec3& p) {
  const double reach = glm::length(p - scene.light_position);
  const glm::dvec3 o = base.texture_from_world(scene.light_position);
  const glm::dvec3 d = base.texture_direction((p - scene.light_position) / reach);  // t: world
  if (!(d.z > 0)) return false;
  const double t_top = (0.0 - o.z) / d.z - kAboveTop / d.z;
  const glm::dvec3 entry = o + d * t_top;
  if (entry.x < 0 || entry.y < 0 || entry.x > scene.tile || entry.y > scene.tile) return false;
  // Up to a hair before p, and no deeper than the relief goes.
  const double t_end = std::min(reach - 1e-4 * scene.size, (bottom - o.z) / d.z);
  return t_end > t_top && truth.occluded(entry, d, 0.0, t_end - t_top);
}

// The loop every truth render shares: one camera ray per pixel, on all cores; the scene's plain
// objects, where one lies in front of the relief's hit; the ray counts. The render's own part,
// `trace(g, i, eye, dir, in_front)`, traces the relief and writes pixel i, after asking
// `in_front(distance)`, which writes the object pixel when an object lies nearer than the
// relief's hit (any distance where it missed) and says so; `object_in_shadow(hit)` says whether
// that object point is in shadow (scene_shadows).
template <typename Truth, typename Trace, typename ObjectInShadow>
GBuffer trace_pixels(const Truth& truth, const SceneDesc& scene, const Camera& camera,
                     const ObjectsTruth* objects, AoTruthCache* ao_cache, TruthStats* stats,
                     TruthCounters& counters, Trace trace, ObjectInShadow object_in_shadow) {
  const auto start = std::chrono::steady_clock::now();
  const uint64_t primary0 = truth.primary_rays(), shadow0 = truth.shadow_rays();
  const size_t ao_reused0 = ao_cache ? ao_cache->reused() : 0;
  GBuffer g;
  g.resize(camera.width, camera.height);
  parallel_for(
      size_t(camera.width) * camera.height,
      [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
          glm::dvec3 eye, dir;
          camera.pixel_ray(int(i % camera.width), int(i / camera.width), eye, dir);
          auto in_front = [&](double relief_distance) {
            if (!objects) return false;
            const ObjectHit oh = objects->intersect(eye, dir, relief_distance);
            if (oh.hit) write_object_pixel(g, i, oh, scene, dir, object_in_shadow(oh));
            return oh.hit;
          };
          trace(g, i, eye, dir, in_front);
        }
      },
      256);
  if (stats) {
    stats->trace_ms = ms_since(start);
    stats->primary_rays =
        truth.primary_rays() - primary0 - counters.relief_rays_from_objects.load();
    stats->shadow_rays = truth.shadow_rays() - shadow0 - counters.ao_traced.load() +
                         counters.object_shadow_rays.load() +
                         counters.relief_rays_from_objects.load();
    stats->ao_rays = counters.ao_rays.load();
    stats->ao_cached_px = ao_cache ? ao_cache->reused() - ao_reused0 : 0;
    stats->unresolved = counters.unresolved.load();
    stats->beyond_quad = counters.beyond_quad.load();
  }
  return g;
}

}  // namespace

AoSampling ao_sampling(const SceneDesc& scene) {
  return {scene.ao.samples, scene.ao.stderr_target};
}

GBuffer render_truth(const TruthSurface& truth, const ReliefMap& map, const SceneDesc& scene,
                     const Camera& camera, EffectSet effects, TruthStats* stats,
                     const ObjectsTruth* objects, AoTruthCache* ao_cache) {
  const PlanarBase base = planar_base(scene);
  const bool shadows = effects.has(Effect::SelfShadow);
  // scene_shadows: every surface shadows every other and itself -- the relief as the light sees
  // it through its quad (relief_blocks_light), and the objects.
  const bool scene_shadows = effects.has(Effect::SceneShadows);
  const bool ambient_occlusion = effects.has(Effect::AmbientOcclusion);
  // Rays end just below the deepest point of the map (not clamped at 1: a map reaching depth 1
  // would put its deepest hits exactly on the end of the ray, where rounding can lose them).
  const double bottom = double(truth.max_depth()) + 1e-4;
  // The truth's bound in world units: its vertical deviation, and its rounding at the scale of
  // a unit of texture space.
  const double vertical_world = truth.vertical_bound() * base.depth;
  const double rounding_world =
      truth.rounding_bound() *
      std::max({glm::length(base.dpdu()), glm::length(base.dpdv()), base.depth});
  TruthCounters counters;
  auto trace = [&](GBuffer& g, size_t i, const glm::dvec3& eye, const glm::dvec3& dir,
                   auto&& in_front) {
    glm::dvec3 o = base.texture_from_world(eye);
    glm::dvec3 d = base.texture_direction(dir);  // t stays the world distance
    const ReverseProjection& projection = scene.projection;
    if (projection.active() && d.z > 0) {
      // Lines stay lines: the ray through the eye and its point at depth 1, projected.
      const glm::dvec3 far = o + d * ((1.0 - o.z) / d.z);
      o = projection.texture_from_affine(o);
      d = projection.texture_from_affine(far) - o;
    }
    double t_start = 0;
    TruthHit h;
    const bool relief = trace_primary(truth, map, scene, o, d, bottom, t_start, h, counters);
    const glm::dvec3 world = projection.active()
                                 ? base.world_from_texture(projection.affine_from_texture(h.point))
                                 : eye + dir * (t_start + h.t);
    // An object in front of the relief's hit (or anywhere, where the relief is missed).
    if (in_front(relief ? glm::length(world - eye) : std::numeric_limits<double>::max())) return;
    if (!relief) return;
    const glm::dvec2 uv(h.point.x, h.point.y);
    const Surface surface = planar_surface(base, map, h, uv, dir);
    const glm::dvec3 to_light = glm::normalize(scene.light_position - world);
    const bool in_shadow =
        (shadows && planar_in_shadow(truth, base, scene, h, world)) ||
        (scene_shadows && (relief_blocks_light(truth, base, scene, bottom, world) ||
                           objects_block_light(objects, scene, world, counters)));
    AoEstimate ao;
    if (ambient_occlusion) {
      // Hemisphere rays from the hit up to where they leave the relief at the top plane
      // (nothing above it blocks), through the tiling as the AO map wraps.
      ao = reference_ao_at(ao_cache, i, h.point, base.normal(), [&] {
        return reference_ao(ao_sampling(scene), ao_seed(i), base.normal(),
                            glm::normalize(base.dpdu()), [&](const glm::dvec3& w) {
                              const glm::dvec3 l = base.texture_direction(w);
                              const double t_exit = -h.point.z / l.z;
                              const double t0 = 1e-4 / std::max(1.0, glm::length(l));
                              if (!(t_exit > t0)) return false;  // at the top: open
                              ++counters.ao_traced;
                              return truth.occluded(h.point, l, t0, t_exit);
                            });
      });
      counters.ao_rays += uint64_t(ao.rays);
    }
    const glm::dvec3& n = surface.normal;
    write_relief_pixel(
        g, i, scene, surface.albedo, n, world, to_light, dir, uv, in_shadow, ao,
        // Every planar truth is exact (vertical 0) or a mesh traced as it is, so the shading
        // normal stands in for the geometric one; a tessellated planar truth would have to
        // supply its own (as DisplacedHit does).
        truth_hit_bound(vertical_world, rounding_world, base.normal(), n, n, dir, world));
  };
  auto object_in_shadow = [&](const ObjectHit& oh) {
    return scene_shadows && (objects_block_light(objects, scene, oh.position, counters) ||
                             relief_blocks_light(truth, base, scene, bottom, oh.position));
  };
  return trace_pixels(truth, scene, camera, objects, ao_cache, stats, counters, trace,
                      object_in_shadow);
}

namespace {

// A secondary ray from hit h: the displaced truth starts its walk in h's prism (the ray
// starts under its sheet); a pattern's Embree scene needs no such start.
bool occluded_from(const DisplacedTruth& truth, const DisplacedHit& h, const glm::dvec3& dir,
                   double t_min, double t_max) {
  return truth.occluded(h.position, dir, t_min, t_max, h.base_triangle);
}
bool occluded_from(const PatternBaseTruth& truth, const DisplacedHit& h, const glm::dvec3& dir,
                   double t_min, double t_max) {
  return truth.occluded(h.position, dir, t_min, t_max);
}

// A relief traced in world space (a displaced heightfield, or a pattern mapped onto the base).
template <typename WorldTruth>
GBuffer render_world_truth(const WorldTruth& truth, const ReliefMap& map, const SceneDesc& scene,
                           const Camera& camera, EffectSet effects, TruthStats* stats,
                           const ObjectsTruth* objects, AoTruthCache* ao_cache) {
  const bool shadows = effects.has(Effect::SelfShadow);
  // scene_shadows: the displaced surface (or the pattern) and the objects shadow every point.
  const bool scene_shadows = effects.has(Effect::SceneShadows);
  const bool ambient_occlusion = effects.has(Effect::AmbientOcclusion);
  const double far = camera.far_plane;
  const double vertical_world = truth.vertical_bound() * scene.depth;
  const double rounding_world = truth.rounding_bound() * std::max(scene.size, scene.depth);
  TruthCounters counters;
  auto trace = [&](GBuffer& g, size_t i, const glm::dvec3& eye, const glm::dvec3& dir,
                   auto&& in_front) {
    const DisplacedHit h = truth.intersect(eye, dir, far);
    if (in_front(h.hit ? h.t : far) || !h.hit) return;
    // Shading as the shaders do it: the map's normal in the base's frame at the hit, or the
    // surface's own normal and colour (a pattern).
    glm::dvec3 n = h.surface_normal, albedo = h.albedo;
    if (!h.has_surface) {
      const glm::dvec3 tn = decode_normal(map.surface_relief(h.uv.x, h.uv.y));
      n = glm::normalize(tn.x * h.tangent + tn.y * h.bitangent + tn.z * h.normal);
      albedo = glm::dvec3(map.sample_color(h.uv.x, h.uv.y));
    }
    const glm::dvec3 to_light = glm::normalize(scene.light_position - h.position);
    bool in_shadow = false;
    if (shadows) {
      if (glm::dot(h.normal, to_light) <= 0) {
        in_shadow = true;  // light at or below the base's tangent plane, as the shaders
      } else {
        const double reach = glm::length(scene.light_position - h.position);
        in_shadow = occluded_from(truth, h, to_light, 1e-4 * scene.depth, reach);
      }
    }
    if (scene_shadows && !in_shadow)
      in_shadow = occluded_from(truth, h, to_light, 1e-4 * scene.depth,
                                glm::length(scene.light_position - h.position)) ||
                  objects_block_light(objects, scene, h.position, counters);
    AoEstimate ao;
    if (ambient_occlusion) {
      // Hemisphere rays about the base's normal, as far as they stay within the relief's shell
      // over a locally flat base: the relief occludes itself, while the base's own shape (a
      // handle over the body) is what no texture-space AO can know.
      const double below_top = scene.depth * map.surface_depth(h.uv.x, h.uv.y) + 1e-6;
      ao = reference_ao_at(ao_cache, i, h.position, h.normal, [&] {
        return reference_ao(
            ao_sampling(scene), ao_seed(i), h.normal, h.tangent, [&](const glm::dvec3& w) {
              const double rise = std::max(glm::dot(w, h.normal), 1e-6);
              ++counters.ao_traced;
              return occluded_from(truth, h, w, 1e-4 * scene.depth, below_top / rise);
            });
      });
      counters.ao_rays += uint64_t(ao.rays);
    }
    const double off_ray = h.off_ray / std::max(std::abs(glm::dot(h.geometric_normal, dir)), 1e-9);
    write_relief_pixel(g, i, scene, albedo, n, h.position, to_light, dir, h.uv, in_shadow, ao,
                       truth_hit_bound(vertical_world, rounding_world, h.normal, h.geometric_normal,
                                       n, dir, h.position) +
                           off_ray);
  };
  auto object_in_shadow = [&](const ObjectHit& oh) {
    if (!scene_shadows) return false;
    if (objects_block_light(objects, scene, oh.position, counters)) return true;
    const WayToLight way = way_to_light(scene, oh.position);
    if (way.length <= 0) return false;
    ++counters.relief_rays_from_objects;
    return truth.intersect(way.origin, way.direction, way.length).hit;
  };
  return trace_pixels(truth, scene, camera, objects, ao_cache, stats, counters, trace,
                      object_in_shadow);
}

}  // namespace

GBuffer render_truth(const DisplacedTruth& truth, const ReliefMap& map, const SceneDesc& scene,
                     const Camera& camera, EffectSet effects, TruthStats* stats,
                     const ObjectsTruth* objects, AoTruthCache* ao_cache) {
  return render_world_truth(truth, map, scene, camera, effects, stats, objects, ao_cache);
}

GBuffer render_truth(const PatternBaseTruth& truth, const ReliefMap& map, const SceneDesc& scene,
                     const Camera& camera, EffectSet effects, TruthStats* stats,
                     const ObjectsTruth* objects, AoTruthCache* ao_cache) {
  return render_world_truth(truth, map, scene, camera, effects, stats, objects, ao_cache);
}

}  // namespace rl
