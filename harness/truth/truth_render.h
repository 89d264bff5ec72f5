#pragma once
// Fills a G-buffer from the Embree truth with the same camera, base frame, tiling, depth
// scale, light and shading formula as the techniques. Shadow rays are traced only when the
// effects ask for self_shadow, hemisphere rays (truth/reference_ao.h) only when they ask for
// ambient_occlusion.
#include <cstdint>

#include "core/effects.h"
#include "core/gbuffer.h"
#include "relief/relief_map.h"
#include "scene/scene.h"
#include "truth/reference_ao.h"
#include "truth/truth_surface.h"

namespace rl {

struct TruthStats {
  double trace_ms = 0;
  uint64_t primary_rays = 0;
  uint64_t shadow_rays = 0;
  uint64_t ao_rays = 0;       // hemisphere rays of the reference ambient occlusion
  uint64_t ao_cached_px = 0;  // pixels whose reference AO came from the AoTruthCache
  long unresolved = 0;        // covered pixels whose ray found no surface (should be 0)
  // A relief impostor: pixels where the object lies but its quad's footprint does not (rays
  // that meet the mesh only outside it), which no render of the quad can show.
  long beyond_quad = 0;
};

// harness/glsl/shading.glsl, in double precision; `ambient_visibility` scales the ambient term
// (ambient occlusion).
glm::dvec3 shade(const Material& m, const glm::dvec3& albedo, const glm::dvec3& n,
                 const glm::dvec3& to_light, const glm::dvec3& to_eye, bool in_shadow,
                 double ambient_visibility = 1.0);

// How far one pixel's truth hit may be from the exact one, as a distance along the camera ray
// `dir` (world units): the truth's surface off by `vertical` (world, along `base_normal`) moves
// the hit by vertical (n . base_normal) / |n . dir|, n the surface's own unit normal
// (`geometric_normal`: a grazing view multiplies the error, 11x at 5 degrees, 57x at 1, more
// where the surface slopes away from the eye); its rounding (`rounding`, world) by
// rounding / |shading_normal . dir|; and storing the position as float rounds each coordinate by
// up to 2^-24 of the largest. Written to the truth G-buffer's aux.w (core/gbuffer.h).
double truth_hit_bound(double vertical, double rounding, const glm::dvec3& base_normal,
                       const glm::dvec3& geometric_normal, const glm::dvec3& shading_normal,
                       const glm::dvec3& dir, const glm::dvec3& position);

// The reference AO's sampling a scene asks for (its ambient_occlusion table).
AoSampling ao_sampling(const SceneDesc& scene);

class ObjectsTruth;
class DisplacedTruth;
class PatternBaseTruth;
class AoTruthCache;

// Each overload takes the scene's objects if any, and `ao_cache` to reuse an earlier run's
// reference AO where the hit is the same (truth/ao_truth_cache.h); the caller saves it.

// A relief on the planar base (texture-space truth), with the scene's objects if given.
GBuffer render_truth(const TruthSurface& truth, const ReliefMap& map, const SceneDesc& scene,
                     const Camera& camera, EffectSet effects, TruthStats* stats = nullptr,
                     const ObjectsTruth* objects = nullptr, AoTruthCache* ao_cache = nullptr);

// A relief on a curved base (world-space displaced truth), with the scene's objects if given.
GBuffer render_truth(const DisplacedTruth& truth, const ReliefMap& map, const SceneDesc& scene,
                     const Camera& camera, EffectSet effects, TruthStats* stats = nullptr,
                     const ObjectsTruth* objects = nullptr, AoTruthCache* ao_cache = nullptr);

// A non-height-field pattern on a curved base (world-space pattern mesh), with objects.
GBuffer render_truth(const PatternBaseTruth& truth, const ReliefMap& map, const SceneDesc& scene,
                     const Camera& camera, EffectSet effects, TruthStats* stats = nullptr,
                     const ObjectsTruth* objects = nullptr, AoTruthCache* ao_cache = nullptr);

}  // namespace rl
