#include "relief/mesh_bake.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <embree3/rtcore.h>

#include "core/embree_util.h"
#include "core/error.h"
#include "core/parallel.h"

namespace rl {

glm::dvec3 BakeFrame::texture_from_mesh(const glm::dvec3& p) const {
  return {(p[axis_u] - origin[axis_u]) / side, (p[axis_v] - origin[axis_v]) / side,
          (origin[up] - p[up]) / height};
}

glm::dvec3 BakeFrame::mesh_from_texture(const glm::dvec3& t) const {
  glm::dvec3 p;
  p[axis_u] = origin[axis_u] + t.x * side;
  p[axis_v] = origin[axis_v] + t.y * side;
  p[up] = origin[up] - t.z * height;
  return p;
}

glm::dvec3 BakeFrame::texture_normal(const glm::dvec3& n) const {
  // Normals transform by the inverse transpose of the (diagonal, flipped-depth) map.
  return glm::normalize(glm::dvec3(n[axis_u] * side, n[axis_v] * side, -n[up] * height));
}

BakeFrame bake_frame(const TriangleMesh& mesh, int up, double margin, double depth_margin) {
  if (up < 0 || up > 2) throw ConfigError("mesh up axis must be x, y or z");
  BakeFrame f;
  f.up = up;
  // Cyclic order keeps (u, v, up) right-handed: the baked object is not mirrored.
  f.axis_u = (up + 1) % 3;
  f.axis_v = (up + 2) % 3;
  const glm::dvec3 extent = mesh.hi - mesh.lo;
  f.side = std::max(extent[f.axis_u], extent[f.axis_v]) * (1 + 2 * margin);
  f.height = std::max(extent[up], 1e-9) * (1 + 2 * depth_margin);
  const glm::dvec3 centre = 0.5 * (mesh.lo + mesh.hi);
  f.origin[f.axis_u] = centre[f.axis_u] - 0.5 * f.side;
  f.origin[f.axis_v] = centre[f.axis_v] - 0.5 * f.side;
  f.origin[up] = mesh.hi[up] + depth_margin * std::max(extent[up], 1e-9);
  return f;
}

ReliefMap bake_mesh(const TriangleMesh& mesh, const BakeFrame& frame, int resolution,
                    const ReverseProjection& projection, const glm::dmat3& face_from_box) {
  const glm::dmat3 box_from_face = glm::transpose(face_from_box);  // a rotation
  auto box_point = [&](const glm::dvec3& a) { return box_from_face * (a - 0.5) + 0.5; };
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = embree_triangle_scene(device, mesh);

  ReliefMap map;
  map.name = mesh.name;
  map.width = map.height = resolution;
  map.relief.resize(size_t(resolution) * resolution);
  map.color.assign(map.relief.size(), glm::vec4(0.78f, 0.74f, 0.70f, 1.0f));
  parallel_for(map.relief.size(), [&](size_t begin, size_t end) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    for (size_t i = begin; i < end; ++i) {
      const int x = int(i % resolution), y = int(i / resolution);
      // In the bake box's affine space (u, v, depth): from just above the texel on the top
      // face, down (orthographic) or towards the centre of projection (reverse perspective),
      // for t in [0, 1] to the bottom.
      const glm::dvec3 a0((x + 0.5) / resolution, (y + 0.5) / resolution, -1e-6);
      const glm::dvec3 da =
          projection.active() ? glm::dvec3(0.5 - a0.x, 0.5 - a0.y, projection.cop) / projection.cop
                              : glm::dvec3(0, 0, 1);
      const glm::dvec3 o = frame.mesh_from_texture(box_point(a0));
      const glm::dvec3 d = frame.mesh_from_texture(box_point(a0 + da)) - o;
      RTCRayHit rh = embree_ray(o, d, 0, 1.0 + 2e-6);
      rtcIntersect1(scene, &ctx, &rh);
      glm::vec4 texel(0.5f, 0.5f, 1.0f, 1.0f);  // floor, facing up
      if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
        const glm::dvec3 n = glm::normalize(glm::dvec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
        // (u, v, up) of the box, then of the face (the identity for the top); facing the
        // viewer above.
        glm::dvec3 tn = face_from_box * glm::dvec3(n[frame.axis_u], n[frame.axis_v], -n[frame.up]);
        tn = glm::dvec3(tn.x, tn.y, -tn.z);
        if (tn.z < 0) tn = -tn;
        // Texture-space depth of the hit (t counts box depths along the affine ray).
        const glm::dvec3 hit = projection.texture_from_affine(a0 + da * double(rh.ray.tfar));
        const double depth = std::clamp(hit.z, 0.0, 1.0);
        texel = glm::vec4(glm::vec3(tn * 0.5 + 0.5), float(depth));
      }
      map.relief[i] = texel;
    }
  });
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  return map;
}

}  // namespace rl
