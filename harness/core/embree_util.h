#pragma once
// Small Embree helpers shared by the truths and the mesh bake.
#include <functional>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "core/triangle_mesh.h"

namespace rl {

// A single ray o + t d, t in [t0, t1], ready for rtcIntersect1 (or .ray for rtcOccluded1).
RTCRayHit embree_ray(const glm::dvec3& o, const glm::dvec3& d, double t0, double t1);

// Is anything of `scene` on o + t d for t in [t0, t1]? (one rtcOccluded1 shadow query)
bool embree_occluded(RTCScene scene, const glm::dvec3& o, const glm::dvec3& d, double t0,
                     double t1);

// Commits `geom`, attaches it to `scene` (which keeps it) and commits the scene.
void attach_and_commit(RTCScene scene, RTCGeometry geom);

// A committed scene of the mesh's triangles, each vertex mapped by `to_space` (e.g. into a
// bake's texture space); identity when empty. The caller releases the scene.
RTCScene embree_triangle_scene(RTCDevice device, const TriangleMesh& mesh,
                               const std::function<glm::dvec3(const glm::dvec3&)>& to_space = {});

}  // namespace rl
