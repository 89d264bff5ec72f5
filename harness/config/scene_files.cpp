#include "config/scene_files.h"

#include <filesystem>
#include <fstream>

#include "core/code_digest.h"
#include "core/error.h"
#include "relief/image_backend.h"
#include "relief/mesh_bake.h"
#include "scene/base_mesh.h"
#include "scene/relief_asset.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

// A file's content hash, hex (read once per run: core/code_digest.h).
std::string content_hash(const std::string& path) {
  return file_digest(path);
}

std::string file_name(const std::string& path) {
  return fs::path(path).filename().string();
}

// "file.obj:0123abcd...": a file's name and content hash, as canonical descriptions hold it.
std::string file_id(const std::string& path) {
  return file_name(path) + ":" + content_hash(path);
}

// The roles an image relief's files are read in (relief/image_io.cpp's load_relief_images): a
// normal map's RGB is the normal and its alpha the depth unless a depth file is given, whose
// first channel is then the depth.
void note_relief_images(const ReliefSourceDesc& r, const std::string& prefix,
                        std::vector<SceneInput>& inputs) {
  auto note = [&](const std::string& path, const std::string& role) {
    if (!path.empty()) inputs.push_back({prefix + role, path, content_hash(path), true});
  };
  note(r.normal_path,
       r.depth_path.empty() ? "normal (RGB normal; depth from alpha)" : "normal (RGB normal)");
  note(r.depth_path, "depth (channel 0)");
  note(r.color_path, "color (RGB)");
}

// An image relief's native size, and its files' hashes into its canonical description.
void read_relief_images(ReliefSourceDesc& r, nlohmann::json& canon, const std::string& site) {
  if (r.normal_path.empty() && r.depth_path.empty()) return;
  const std::string& sized = r.depth_path.empty() ? r.normal_path : r.depth_path;
  ImageHeader header;
  std::string error;
  if (!image_backend().read_header(sized, header, error))
    throw ConfigError(site + ": cannot read image " + sized + ": " + error);
  r.native = {header.width, header.height};
  for (const std::string* p : {&r.normal_path, &r.depth_path, &r.color_path})
    if (!p->empty()) canon["files"].push_back({file_name(*p), content_hash(*p)});
}

}  // namespace

void read_scene_files(ParsedScene& parsed) {
  SceneDesc& s = parsed.scene;
  ReliefSourceDesc& r = s.relief;
  nlohmann::json& canon = parsed.canon;
  auto mesh_at = [&](const std::string& site, const std::string& path) {
    try {
      return load_mesh(path);
    } catch (const ConfigError& e) {
      throw ConfigError(site + ": scene '" + s.name + "': " + e.what());
    }
  };
  read_relief_images(r, canon["relief"], parsed.sites.relief);
  note_relief_images(r, "relief ", parsed.inputs);
  for (size_t i = 0; i < s.meta.layers.size(); ++i) {
    read_relief_images(s.meta.layers[i].relief, canon["meta_relief"]["layers"][i]["relief"],
                       parsed.sites.relief);
    note_relief_images(s.meta.layers[i].relief, "meta_relief layer " + std::to_string(i + 1) + " ",
                       parsed.inputs);
  }
  if (!r.mesh_path.empty()) {
    canon["relief"]["mesh"] = file_id(r.mesh_path);
    parsed.inputs.push_back({r.cells.active ? "relief cells (mesh)" : "relief mesh", r.mesh_path,
                             content_hash(r.mesh_path)});
  }
  if (!r.mesh_path.empty() && !s.base.curved()) {
    // A baked mesh keeps its proportions: the relief depth follows from the footprint.
    const TriangleMesh mesh = mesh_at(parsed.sites.relief, r.mesh_path);
    r.mesh_triangles = mesh.triangles.size();
    const BakeFrame frame = relief_bake_frame(r, mesh);
    s.depth = s.size * frame.height / frame.side;
    canon["depth"] = s.depth;
  }
  if (s.base.kind == "file") {
    const TriangleMesh base = mesh_at(parsed.sites.base, s.base.path);
    if (base.uvs.empty())
      throw ConfigError(parsed.sites.base + ": base mesh " + s.base.path +
                        " has no texture coordinates; a relief needs a uv mapping");
    try {
      check_base_uvs(base);
    } catch (const ConfigError& e) {
      throw ConfigError(parsed.sites.base + ": scene '" + s.name + "': " + e.what());
    }
    canon["base_file"] = file_id(s.base.path);
    parsed.inputs.push_back({"base mesh", s.base.path, content_hash(s.base.path)});
  }
  for (size_t i = 0; i < s.objects.size(); ++i) {
    const std::string& shape = s.objects[i].shape;
    if (shape == "sphere" || shape == "cube") continue;
    canon["objects"][i][0] = file_id(shape);
    parsed.inputs.push_back(
        {"object " + std::to_string(i + 1) + " mesh", shape, content_hash(shape)});
  }
}

}  // namespace rl
