#include "core/triangle_mesh.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "core/error.h"

namespace rl {
namespace {

// Bytes of a PLY scalar type, 0 when unknown.
size_t ply_type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32")
    return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

// A PLY header states its element counts; Assimp believes them, so a file declaring 10 M faces
// and holding 4 became 10 M triangles to bake. Checks the data can hold what the header
// declares: a line per element in ASCII, the smallest size of each element in binary (a face's
// list at least a triangle). Throws ConfigError naming the file.
void check_ply_counts(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line, format;
  struct Element {
    std::string name;
    long long count = 0;
    size_t min_bytes = 0;
  };
  std::vector<Element> elements;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "end_header") break;
    if (word == "format") words >> format;
    if (word == "element") {
      Element e;
      words >> e.name >> e.count;
      elements.push_back(e);
    }
    if (word == "property" && !elements.empty()) {
      std::string type, count_type, item_type;
      words >> type;
      if (type == "list") {
        words >> count_type >> item_type;
        const size_t items = elements.back().name == "face" ? 3 : 0;
        elements.back().min_bytes += ply_type_size(count_type) + items * ply_type_size(item_type);
      } else {
        elements.back().min_bytes += ply_type_size(type);
      }
    }
  }
  if (!in) return;  // no header end: Assimp's own error names it
  const std::streamoff data_start = in.tellg();
  long long declared = 0, lines = 0;
  long double bytes = 0;
  for (const Element& e : elements) {
    if (e.count < 0)
      throw ConfigError("mesh " + path + ": element " + e.name + " has a negative count");
    declared += e.count;
    bytes += (long double)e.count * (long double)e.min_bytes;
  }
  std::string description;
  for (const Element& e : elements)
    description += (description.empty() ? "" : ", ") + std::to_string(e.count) + " " + e.name;
  if (format == "ascii") {
    for (std::string data; std::getline(in, data);)
      lines += data.find_first_not_of(" \t\r") != std::string::npos;
    if (lines < declared)
      throw ConfigError("mesh " + path + ": its header declares " + description + " (" +
                        std::to_string(declared) + " lines of data) but it holds " +
                        std::to_string(lines) + " (cut short, or a wrong count)");
    return;
  }
  const long double size = (long double)std::filesystem::file_size(path) - (long double)data_start;
  if (size < bytes)
    throw ConfigError("mesh " + path + ": its header declares " + description + ", at least " +
                      std::to_string((long long)bytes) + " bytes of data, but it holds " +
                      std::to_string((long long)size) + " (cut short, or a wrong count)");
}

// Assimp's meshes, triangulated, in one list; texture coordinates only if every mesh has them.
TriangleMesh mesh_from_scene(const aiScene& scene, const std::string& path) {
  TriangleMesh m;
  m.name = path;
  bool all_uvs = true;
  for (unsigned mi = 0; mi < scene.mNumMeshes; ++mi) {
    const aiMesh* am = scene.mMeshes[mi];
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
  return m;
}

// Input that would measure nothing, or measure garbage, is an error naming the file: values
// that are not finite or too large to render, and faces naming vertices the file lacks.
void check_values(const TriangleMesh& m, const std::string& path) {
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
}

// A mesh whose triangles all have no area, or only slivers beside its extent (a stray vertex
// far from the rest), is an error naming the file and the vertex.
void check_not_degenerate(const TriangleMesh& m, const std::string& path) {
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
  if (largest_area > 1e-12 * extent * extent) return;
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

}  // namespace

TriangleMesh load_mesh(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".ply") check_ply_counts(path);
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_PreTransformVertices);
  if (!scene)
    throw ConfigError("cannot read mesh " + path + ": " + one_line(importer.GetErrorString()));
  TriangleMesh m = mesh_from_scene(*scene, path);
  check_values(m, path);
  m.lo = m.hi = glm::dvec3(m.positions[0]);
  for (const auto& p : m.positions) {
    m.lo = glm::min(m.lo, glm::dvec3(p));
    m.hi = glm::max(m.hi, glm::dvec3(p));
  }
  check_not_degenerate(m, path);
  return m;
}

MeshClosure mesh_closure(const TriangleMesh& mesh) {
  // Weld: one id per distinct position.
  std::map<std::tuple<float, float, float>, uint32_t> ids;
  std::vector<uint32_t> id(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    id[i] = ids.emplace(std::make_tuple(p.x, p.y, p.z), uint32_t(ids.size())).first->second;
  }
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (const glm::uvec3& t : mesh.triangles) {
    const uint32_t v[3] = {id[t.x], id[t.y], id[t.z]};
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;  // collapsed by the weld
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(v[k], v[(k + 1) % 3])];
  }
  MeshClosure c;
  for (const auto& [edge, n] : uses) {
    c.boundary_edges += n == 1;
    c.non_manifold_edges += n > 2;
  }
  return c;
}

}  // namespace rl
