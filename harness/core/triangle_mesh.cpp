#include "core/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "core/error.h"

namespace rl {

TriangleMesh load_mesh(const std::string& path) {
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_PreTransformVertices);
  if (!scene)
    throw ConfigError("cannot read mesh " + path + ": " + one_line(importer.GetErrorString()));
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
  glm::dvec3 largest_centre(0);
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 a(m.positions[t.x]), b(m.positions[t.y]), c(m.positions[t.z]);
    const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
    if (area > largest_area) largest_area = area, largest_centre = (a + b + c) / 3.0;
  }
  if (!(extent > 0) || !(largest_area > 0))
    throw ConfigError("mesh " + path + " is degenerate: every triangle has zero area");
  if (!(largest_area > 1e-12 * extent * extent)) {
    // Triangles with area, dwarfed by the extent: a vertex far from the rest.
    size_t far = 0;
    for (size_t i = 1; i < m.positions.size(); ++i)
      if (glm::length(glm::dvec3(m.positions[i]) - largest_centre) >
          glm::length(glm::dvec3(m.positions[far]) - largest_centre))
        far = i;
    const glm::vec3 p = m.positions[far];
    char text[256];
    std::snprintf(text, sizeof text,
                  ": its triangles are slivers beside its extent of %.3g (the largest has area "
                  "%.3g): vertex %zu lies at (%.3g, %.3g, %.3g), far from the rest (a stray "
                  "vertex?)",
                  extent, largest_area, far, p.x, p.y, p.z);
    throw ConfigError("mesh " + path + text);
  }
  return m;
}

}  // namespace rl
