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
#include "truth/truth_surface.h"

namespace rl {

struct TruthStats {
  double trace_ms = 0;
  uint64_t primary_rays = 0;
  uint64_t shadow_rays = 0;
  uint64_t ao_rays = 0;  // hemisphere rays of the reference ambient occlusion
  long unresolved = 0;   // covered pixels whose ray found no surface (should be 0)
};

// harness/glsl/shading.glsl, in double precision; `ambient_visibility` scales the ambient term
// (ambient occlusion).
glm::dvec3 shade(const Material& m, const glm::dvec3& albedo, const glm::dvec3& n,
                 const glm::dvec3& to_light, const glm::dvec3& to_eye, bool in_shadow,
                 double ambient_visibility = 1.0);

class ObjectsTruth;
class DisplacedTruth;
class PatternBaseTruth;

// A relief on the planar base (texture-space truth), with the scene's objects if given.
GBuffer render_truth(const TruthSurface& truth, const ReliefMap& map, const SceneDesc& scene,
                     const Camera& camera, EffectSet effects, TruthStats* stats = nullptr,
                     const ObjectsTruth* objects = nullptr);

// A relief on a curved base (world-space displaced truth), with the scene's objects if given.
GBuffer render_truth(const DisplacedTruth& truth, const ReliefMap& map, const SceneDesc& scene,
                     const Camera& camera, EffectSet effects, TruthStats* stats = nullptr,
                     const ObjectsTruth* objects = nullptr);

// A non-height-field pattern on a curved base (world-space pattern mesh), with objects.
GBuffer render_truth(const PatternBaseTruth& truth, const ReliefMap& map, const SceneDesc& scene,
                     const Camera& camera, EffectSet effects, TruthStats* stats = nullptr,
                     const ObjectsTruth* objects = nullptr);

}  // namespace rl
