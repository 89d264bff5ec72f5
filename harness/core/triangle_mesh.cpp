#include "core/triangle_mesh.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <list>
#include <map>
#include <mutex>
#include <sstream>
#include <tuple>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "core/error.h"
#include "core/hash.h"

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

struct PlyProperty {
  std::string type, count_type, name;  // count_type: a list's, empty for a scalar
};
struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};
struct PlyHeader {
  std::string format;
  std::vector<PlyElement> elements;
  std::streamoff data_start = -1;  // -1: no end_header
};

PlyHeader read_ply_header(std::ifstream& in, const std::string& path) {
  PlyHeader h;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "end_header") {
      h.data_start = in.tellg();
      break;
    }
    if (word == "format") words >> h.format;
    if (word == "element") {
      PlyElement e;
      words >> e.name >> e.count;
      if (e.count < 0)
        throw ConfigError("mesh " + path + ": element " + e.name + " has a negative count");
      h.elements.push_back(e);
    }
    if (word == "property" && !h.elements.empty()) {
      PlyProperty p;
      words >> p.type;
      if (p.type == "list") words >> p.count_type >> p.type;
      words >> p.name;
      h.elements.back().properties.push_back(p);
    }
  }
  return h;
}

// Reads a PLY file's data one value at a time, ASCII or binary (either byte order).
class PlyValues {
 public:
  PlyValues(std::ifstream& in, const std::string& format) : in_(in), format_(format) {}
  bool ascii() const { return format_ == "ascii"; }
  // The next value of `type` as a double; false at the end of the data.
  bool next(const std::string& type, double& v) {
    if (ascii()) return bool(in_ >> v);
    unsigned char b[8];
    const size_t n = ply_type_size(type);
    if (!n || !in_.read(reinterpret_cast<char*>(b), std::streamsize(n))) return false;
    if (format_ == "binary_big_endian") std::reverse(b, b + n);
    auto as = [&](auto x) {
      std::memcpy(&x, b, sizeof x);
      return double(x);
    };
    const bool is_signed = type[0] != 'u', is_float = type[0] == 'f' || type[0] == 'd';
    if (is_float)
      v = n == 4 ? as(float()) : as(double());
    else if (n == 1)
      v = is_signed ? as(int8_t()) : as(uint8_t());
    else if (n == 2)
      v = is_signed ? as(int16_t()) : as(uint16_t());
    else
      v = is_signed ? as(int32_t()) : as(uint32_t());
    return true;
  }

 private:
  std::ifstream& in_;
  std::string format_;
};

std::string ply_element_at(const PlyElement& e, long long i) {
  return e.name + " " + std::to_string(i) + " of " + std::to_string(e.count);
}

// A PLY header states its element counts and Assimp believes them, and it indexes vertices
// with what the faces say: a header declaring 10 M faces and holding 4 became 10 M triangles
// to bake, a face naming a vertex past the end or below zero crashed the process, and a header
// declaring fewer vertices than the file holds read the rest as faces. So every element is read
// here first, as the header declares it: each value present, face indices naming vertices the
// file holds, and in ASCII nothing after the last element. Throws ConfigError naming the file and
// the item.
void check_ply(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const PlyHeader h = read_ply_header(in, path);
  // Assimp was seen to loop on a header without its end.
  if (h.data_start < 0)
    throw ConfigError("mesh " + path + ": its PLY header has no end_header line");
  if (h.format != "ascii" && h.format != "binary_little_endian" && h.format != "binary_big_endian")
    throw ConfigError("mesh " + path + ": unknown PLY format '" + h.format +
                      "' (ascii, binary_little_endian or binary_big_endian)");
  long long vertices = 0;
  for (const PlyElement& e : h.elements)
    if (e.name == "vertex") vertices = e.count;
  PlyValues values(in, h.format);
  std::string declared;
  for (const PlyElement& e : h.elements)
    declared += (declared.empty() ? "" : ", ") + std::to_string(e.count) + " " + e.name;
  const std::string short_data =
      " (its header declares " + declared + ": cut short, or a wrong count?)";
  for (const PlyElement& e : h.elements)
    for (long long i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.properties) {
        double count = 1, v = 0;
        if (!p.count_type.empty() && !values.next(p.count_type, count))
          throw ConfigError("mesh " + path + ": no data for " + ply_element_at(e, i) + short_data);
        if (!(count >= 0 && count <= 1 << 16))
          throw ConfigError("mesh " + path + ": " + ply_element_at(e, i) + " has a list of " +
                            std::to_string(count) + " items");
        for (int k = 0; k < int(count); ++k) {
          if (!values.next(p.type, v))
            throw ConfigError("mesh " + path + ": no data for " + ply_element_at(e, i) +
                              short_data);
          const bool index =
              e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index");
          if (index && !(v >= 0 && v < double(vertices) && v == std::floor(v)))
            throw ConfigError("mesh " + path + ": " + ply_element_at(e, i) + " names vertex " +
                              std::to_string((long long)v) + ", but the file holds " +
                              std::to_string(vertices) + " (0 to " + std::to_string(vertices - 1) +
                              ")");
        }
      }
  // In ASCII the values left over would be read as the next element's (binary files may end
  // in padding).
  double extra = 0;
  if (values.ascii() && in >> extra)
    throw ConfigError("mesh " + path +
                      ": it holds more data than its header declares (a wrong count?)");
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

// The material libraries an OBJ names are opened by Assimp: one that is not a regular file (a
// FIFO hangs the reader) is an error naming it; a missing one Assimp skips.
void check_obj_material_library(const std::string& path, std::istringstream& words) {
  std::string name;
  while (words >> name) {
    const std::filesystem::path lib = std::filesystem::path(path).parent_path() / name;
    std::error_code ec;
    const auto st = std::filesystem::status(lib, ec);
    if (!ec && std::filesystem::exists(st) && !std::filesystem::is_regular_file(st))
      throw ConfigError("mesh " + path + ": its material library " + lib.string() +
                        " is not a regular file");
  }
}

// The indices an OBJ face names ("v", "v/vt", "v//vn", "v/vt/vn"), each checked against the
// lines of its kind: a negative one against those read so far, a positive one, which may look
// ahead, against the file's count at its end (`ahead`: the largest positive index of each kind
// and the line that named it). Assimp drops a uv index past the end and reads the mesh as
// having none, which a base mesh then reported as "no texture coordinates".
struct ObjIndexUse {
  long largest = 0;
  int line = 0;
};
void check_obj_face(const std::string& path, int number, std::istringstream& words,
                    const std::array<long, 3>& counts, std::array<ObjIndexUse, 3>& ahead) {
  static const char* kinds[3] = {"vertex", "texture coordinate", "normal"};
  for (std::string corner; words >> corner && corner[0] != '#';) {
    std::istringstream parts(corner);
    std::string index;
    for (int k = 0; k < 3 && std::getline(parts, index, '/'); ++k) {
      if (index.empty()) continue;
      char* end = nullptr;
      const long i = std::strtol(index.c_str(), &end, 10);
      const bool bad = *end != '\0' || i == 0 || (i < 0 && -i > counts[size_t(k)]);
      if (bad)
        throw ConfigError("mesh " + path + ":" + std::to_string(number) + ": a face names " +
                          kinds[k] + " " + index.substr(0, 20) + " of " +
                          std::to_string(counts[size_t(k)]) + " defined so far");
      if (i > ahead[size_t(k)].largest) ahead[size_t(k)] = {i, number};
    }
  }
}

// What Assimp reads of an OBJ without a word: its material libraries, the numbers of its
// vertex lines (it reads "nan" in a texture coordinate as 0, so a NaN uv was accepted) and the
// indices its faces name.
void check_obj(const std::string& path) {
  static const char* kinds[3] = {"vertex", "texture coordinate", "normal"};
  std::ifstream in(path);
  int number = 0;
  std::array<long, 3> counts{};  // v, vt, vn lines
  std::array<ObjIndexUse, 3> ahead{};
  for (std::string line; std::getline(in, line);) {
    ++number;
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "mtllib") check_obj_material_library(path, words);
    if (word == "f") check_obj_face(path, number, words, counts, ahead);
    if (word != "v" && word != "vt" && word != "vn") continue;
    ++counts[word == "v" ? 0 : word == "vt" ? 1 : 2];
    for (std::string value; words >> value && value[0] != '#';) {
      char* end = nullptr;
      const double x = std::strtod(value.c_str(), &end);
      if (end == value.c_str() || *end != '\0' || !std::isfinite(x))
        throw ConfigError("mesh " + path + ":" + std::to_string(number) + ": '" + word +
                          "' value '" + value.substr(0, 40) + "' is not a finite number");
    }
  }
  for (size_t k = 0; k < 3; ++k)
    if (ahead[k].largest > counts[k])
      throw ConfigError("mesh " + path + ":" + std::to_string(ahead[k].line) + ": a face names " +
                        kinds[k] + " " + std::to_string(ahead[k].largest) + " of " +
                        std::to_string(counts[k]) + " the file defines");
}

// Reads and checks the file; load_mesh() keeps what it read.
TriangleMesh read_mesh_file(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  // OBJ and PLY only, the formats whose files are checked before Assimp reads them: its other
  // importers took files they abort on (a truncated OFF ended the process in its triangulation).
  if (extension != ".obj" && extension != ".ply")
    throw ConfigError("mesh " + path + ": '" + extension +
                      "' is not read; meshes are OBJ (.obj) or PLY (.ply) files");
  if (extension == ".ply") check_ply(path);
  if (extension == ".obj") check_obj(path);
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

// The meshes a process read, by path and content: a config, its check, its asset and its truth
// each load the relief's mesh, and `verify` loads the same meshes for many folders' configs.
// Keyed by the bytes (hashing them is a small part of parsing them), not by a file's time
// stamp, which a file rewritten within a clock tick keeps. The oldest go past kMemoBytes.
struct MemoMesh {
  uint64_t content = 0;
  TriangleMesh mesh;
};
constexpr size_t kMemoBytes = size_t(256) << 20;

size_t mesh_bytes(const TriangleMesh& m) {
  return m.positions.size() * sizeof(glm::vec3) + m.uvs.size() * sizeof(glm::vec2) +
         m.triangles.size() * sizeof(glm::uvec3) + m.triangle_colors.size() * sizeof(glm::vec3);
}

std::mutex& memo_mutex() {
  static std::mutex m;
  return m;
}
std::list<std::pair<std::string, MemoMesh>>& memo() {  // newest first
  static std::list<std::pair<std::string, MemoMesh>> meshes;
  return meshes;
}

void remember(const std::string& path, uint64_t content, const TriangleMesh& mesh) {
  if (mesh_bytes(mesh) > kMemoBytes) return;
  auto& meshes = memo();
  std::erase_if(meshes, [&](const auto& entry) { return entry.first == path; });
  meshes.push_front({path, {content, mesh}});
  size_t bytes = 0;
  for (auto it = meshes.begin(); it != meshes.end(); ++it) {
    bytes += mesh_bytes(it->second.mesh);
    if (bytes > kMemoBytes) {
      meshes.erase(it, meshes.end());
      break;
    }
  }
}

}  // namespace

TriangleMesh load_mesh(const std::string& path) {
  // The bytes hashed before they are parsed: a file rewritten between the two is read again.
  const uint64_t content = file_content_hash(path);
  {
    const std::lock_guard<std::mutex> lock(memo_mutex());
    for (const auto& [at, kept] : memo())
      if (at == path && kept.content == content) return kept.mesh;
  }
  TriangleMesh mesh = read_mesh_file(path);
  const std::lock_guard<std::mutex> lock(memo_mutex());
  remember(path, content, mesh);
  return mesh;
}

std::vector<uint32_t> welded_vertex_ids(const TriangleMesh& mesh) {
  std::map<std::tuple<float, float, float>, uint32_t> ids;
  std::vector<uint32_t> id(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    id[i] = ids.emplace(std::make_tuple(p.x, p.y, p.z), uint32_t(ids.size())).first->second;
  }
  return id;
}

MeshClosure mesh_closure(const TriangleMesh& mesh) {
  const std::vector<uint32_t> id = welded_vertex_ids(mesh);
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
