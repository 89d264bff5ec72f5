#include "relief/mesh_bake.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <embree3/rtcore.h>
#include <assimp/Importer.hpp>

#include "core/embree_util.h"
#include "core/error.h"
#include "core/parallel.h"

namespace rl {

TriangleMesh load_mesh(const std::string& path) {
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_PreTransformVertices);
  if (!scene) throw ConfigError("cannot read mesh " + path + ": " + importer.GetErrorString());
  TriangleMesh m;
  m.name = path;
  bool all_uvs = true;
  for (unsigned mi = 0; mi < scene->mNumMeshes; ++mi) {
    const aiMesh* am = scene->mMeshes[mi];
    const unsigned base = unsigned(m.positions.size());
    const aiVector3D* uv = am->HasTextureCoords(0) ? am->mTextureCoords[0] : nullptr;
    all_uvs = all_uvs && uv;
    for (unsigned v = 0; v < am->mNumVertices; ++v) {
      m.positions.push_back(glm::vec3(am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z));
      if (uv) m.uvs.push_back(glm::vec2(uv[v].x, uv[v].y));
    }
    for (unsigned f = 0; f < am->mNumFaces; ++f)
      if (am->mFaces[f].mNumIndices == 3)
        m.triangles.push_back(glm::uvec3(base + am->mFaces[f].mIndices[0],
                                         base + am->mFaces[f].mIndices[1],
                                         base + am->mFaces[f].mIndices[2]));
  }
  if (m.triangles.empty()) throw ConfigError("mesh " + path + " holds no triangles");
  if (!all_uvs) m.uvs.clear();
  // Input that would measure nothing, or measure garbage, is an error naming the file.
  constexpr double kLargest = 1e15;  // beyond this, float positions lose all precision in GL
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const glm::vec3& p = m.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw ConfigError("mesh " + path + ": vertex " + std::to_string(i) +
                        " has a non-finite coordinate");
    if (std::abs(p.x) > kLargest || std::abs(p.y) > kLargest || std::abs(p.z) > kLargest)
      throw ConfigError("mesh " + path + ": vertex " + std::to_string(i) +
                        " lies beyond 1e15 (coordinates this large cannot be rendered)");
  }
  for (const glm::uvec3& t : m.triangles)
    if (std::max({t.x, t.y, t.z}) >= m.positions.size())
      throw ConfigError("mesh " + path +
                        ": a face refers to a vertex the file does not hold "
                        "(malformed vertex line?)");
  for (const auto& uv : m.uvs)
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
      throw ConfigError("mesh " + path + ": a texture coordinate is not finite");
  m.lo = m.hi = glm::dvec3(m.positions[0]);
  for (const auto& p : m.positions) {
    m.lo = glm::min(m.lo, glm::dvec3(p));
    m.hi = glm::max(m.hi, glm::dvec3(p));
  }
  const double extent = glm::length(m.hi - m.lo);
  double largest_area = 0;
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 a(m.positions[t.x]), b(m.positions[t.y]), c(m.positions[t.z]);
    largest_area = std::max(largest_area, 0.5 * glm::length(glm::cross(b - a, c - a)));
  }
  if (!(extent > 0) || !(largest_area > 1e-12 * extent * extent))
    throw ConfigError("mesh " + path + " is degenerate: every triangle has zero area");
  return m;
}

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

BakeFrame bake_frame(const TriangleMesh& mesh, int up, double margin) {
  if (up < 0 || up > 2) throw ConfigError("mesh up axis must be x, y or z");
  BakeFrame f;
  f.up = up;
  // Cyclic order keeps (u, v, up) right-handed: the baked object is not mirrored.
  f.axis_u = (up + 1) % 3;
  f.axis_v = (up + 2) % 3;
  const glm::dvec3 extent = mesh.hi - mesh.lo;
  f.side = std::max(extent[f.axis_u], extent[f.axis_v]) * (1 + 2 * margin);
  f.height = std::max(extent[up], 1e-9);
  const glm::dvec3 centre = 0.5 * (mesh.lo + mesh.hi);
  f.origin[f.axis_u] = centre[f.axis_u] - 0.5 * f.side;
  f.origin[f.axis_v] = centre[f.axis_v] - 0.5 * f.side;
  f.origin[up] = mesh.hi[up];
  return f;
}

ReliefMap bake_mesh(const TriangleMesh& mesh, const BakeFrame& frame, int resolution,
                    const ReverseProjection& projection) {
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
      const glm::dvec3 o = frame.mesh_from_texture(a0);
      const glm::dvec3 d = frame.mesh_from_texture(a0 + da) - o;
      RTCRayHit rh = embree_ray(o, d, 0, 1.0 + 2e-6);
      rtcIntersect1(scene, &ctx, &rh);
      glm::vec4 texel(0.5f, 0.5f, 1.0f, 1.0f);  // floor, facing up
      if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
        glm::dvec3 n = glm::normalize(glm::dvec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
        if (n[frame.up] < 0) n = -n;  // face the viewer above
        const glm::dvec3 tn(n[frame.axis_u], n[frame.axis_v], n[frame.up]);
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
