#include "sweep/config.h"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <OpenImageIO/imageio.h>
#include <toml++/toml.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/hash.h"
#include "gl/embedded_files.h"
#include "relief/mesh_bake.h"
#include "relief/procedural.h"
#include "sweep/cells.h"
#include "technique/technique.h"

namespace rl {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Context for messages: "file:line: what".
struct Src {
  std::string file;
  std::string at(const toml::node& n) const {
    return file + ":" + std::to_string(n.source().begin.line);
  }
};

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw ConfigError(where + ": " + what);
}

void check_keys(const toml::table& t, const std::set<std::string>& allowed, const Src& src,
                const std::string& section) {
  for (auto&& [k, v] : t) {
    if (!allowed.count(std::string(k.str()))) {
      std::string known;
      for (const auto& a : allowed) known += (known.empty() ? "" : ", ") + a;
      fail(src.at(v),
           "unknown key '" + std::string(k.str()) + "' in " + section + " (known: " + known + ")");
    }
  }
}

double number(const toml::node& n, const Src& src, const std::string& key) {
  if (auto v = n.value<double>(); v && (n.is_integer() || n.is_floating_point())) return *v;
  if (n.is_boolean()) return n.value<bool>().value() ? 1.0 : 0.0;
  fail(src.at(n), "'" + key + "' must be a number");
}

std::string string_of(const toml::node& n, const Src& src, const std::string& key) {
  if (auto v = n.value<std::string>()) return *v;
  fail(src.at(n), "'" + key + "' must be a string");
}

// A scalar or an array of scalars, as a list of numbers.
std::vector<double> number_list(const toml::node& n, const Src& src, const std::string& key) {
  std::vector<double> out;
  if (const toml::array* a = n.as_array()) {
    if (a->empty()) fail(src.at(n), "'" + key + "' must not be empty");
    for (const toml::node& e : *a) out.push_back(number(e, src, key));
  } else {
    out.push_back(number(n, src, key));
  }
  return out;
}

std::vector<std::string> string_list(const toml::node& n, const Src& src, const std::string& key) {
  std::vector<std::string> out;
  if (const toml::array* a = n.as_array()) {
    for (const toml::node& e : *a) out.push_back(string_of(e, src, key));
  } else {
    out.push_back(string_of(n, src, key));
  }
  return out;
}

glm::dvec3 vec3_of(const toml::node& n, const Src& src, const std::string& key) {
  std::vector<double> v = number_list(n, src, key);
  if (v.size() != 3) fail(src.at(n), "'" + key + "' must be an array of 3 numbers");
  return {v[0], v[1], v[2]};
}

std::string resolve_path(const std::string& p, const std::string& base_dir, const Src& src,
                         const toml::node& n) {
  fs::path path(p);
  if (path.is_absolute()) {
    if (!fs::exists(path)) fail(src.at(n), "file not found: " + p);
    return path.string();
  }
  for (const fs::path& dir : {fs::path(base_dir), fs::path(RELIEFLAB_SOURCE_DIR)}) {
    fs::path candidate = dir / path;
    if (fs::exists(candidate)) return fs::weakly_canonical(candidate).string();
  }
  fail(src.at(n),
       "file not found: " + p + " (looked in " + base_dir + " and " + RELIEFLAB_SOURCE_DIR + ")");
}

uint64_t file_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return fnv1a64(bytes);
}

bool is_measured(const std::string& name) {
  const auto& m = measured_columns();
  return std::find(m.begin(), m.end(), name) != m.end();
}

std::string measured_list() {
  std::string out;
  for (const auto& m : measured_columns()) out += (out.empty() ? "" : ", ") + m;
  return out;
}

int positive_int(const toml::node& n, const Src& src, const std::string& key, int lo, int hi) {
  double v = number(n, src, key);
  if (v != std::floor(v) || v < lo || v > hi)
    fail(src.at(n), "'" + key + "' must be an integer in [" + std::to_string(lo) + ", " +
                        std::to_string(hi) + "], got " + std::to_string(v));
  return int(v);
}

ReliefSourceDesc parse_relief(const toml::node& node, const Src& src, const std::string& base_dir,
                              json& canon) {
  const toml::table* t = node.as_table();
  if (!t) fail(src.at(node), "'relief' must be a table, e.g. { procedural = \"bricks\" }");
  check_keys(*t,
             {"procedural", "resolution", "options", "normal", "depth", "color", "convention",
              "flip_green", "normalize", "mesh", "up", "reverse_perspective"},
             src, "relief");
  ReliefSourceDesc r;
  const bool procedural = t->contains("procedural");
  const bool images = t->contains("normal") || t->contains("depth");
  const bool mesh = t->contains("mesh");
  if (int(procedural) + int(images) + int(mesh) != 1)
    fail(src.at(node),
         "relief needs exactly one of 'procedural', image files ('normal' and/or "
         "'depth') or 'mesh'");
  if (mesh) {
    for (const char* k : {"color", "convention", "flip_green", "normalize", "options"})
      if (t->contains(k))
        fail(src.at(node), std::string("'") + k + "' does not apply to a mesh relief");
    const toml::node& mn = *t->get("mesh");
    r.mesh_path = resolve_path(string_of(mn, src, "mesh"), base_dir, src, mn);
    if (auto* n = t->get("up")) {
      const std::string up = string_of(*n, src, "up");
      if (up != "x" && up != "y" && up != "z")
        fail(src.at(*n), "'up' must be \"x\", \"y\" or \"z\"");
      r.mesh_up = up[0] - 'x';
    }
    if (auto* n = t->get("resolution")) {
      const int res = positive_int(*n, src, "resolution", 2, 8192);
      r.native = {res, res};
    }
    canon["mesh"] = fs::path(r.mesh_path).filename().string() + ":" + hex64(file_hash(r.mesh_path));
    canon["up"] = r.mesh_up;
    if (auto* n = t->get("reverse_perspective")) {
      r.reverse_cop = number(*n, src, "reverse_perspective");
      if (!(r.reverse_cop > 1) || !std::isfinite(r.reverse_cop))
        fail(src.at(*n),
             "'reverse_perspective' is the depth of the centre of projection below the "
             "top, in box depths: it must be > 1, got " +
                 std::to_string(r.reverse_cop));
      canon["reverse_perspective"] = r.reverse_cop;
    }
    canon["resolution"] = r.native.width;
    return r;
  }
  if (t->contains("up") || t->contains("reverse_perspective"))
    fail(src.at(node), "'up' and 'reverse_perspective' apply to mesh reliefs only");
  if (procedural) {
    r.procedural = string_of(*t->get("procedural"), src, "procedural");
    bool known = false;
    for (const auto& k : procedural_kinds()) known |= k.name == r.procedural;
    if (!known) {
      std::string names;
      for (const auto& k : procedural_kinds()) names += (names.empty() ? "" : ", ") + k.name;
      fail(src.at(*t->get("procedural")),
           "unknown procedural relief '" + r.procedural + "' (known: " + names + ")");
    }
    if (auto* n = t->get("resolution")) {
      const int res = positive_int(*n, src, "resolution", 2, 8192);
      r.native = {res, res};
    }
    if (auto* o = t->get("options")) {
      const toml::table* ot = o->as_table();
      if (!ot) fail(src.at(*o), "'options' must be a table");
      for (auto&& [k, v] : *ot)
        r.options[std::string(k.str())] = number(v, src, std::string(k.str()));
      // Validate option names now (make_procedural checks them the same way).
      make_procedural(r.procedural, 4, r.options, 1.0, src.at(*o));
    }
    canon["procedural"] = r.procedural;
    canon["options"] = r.options;
    canon["resolution"] = r.native.width;
    return r;
  }
  if (t->contains("resolution") || t->contains("options"))
    fail(src.at(node), "'resolution' and 'options' apply to procedural reliefs only");
  if (auto* n = t->get("normal"))
    r.normal_path = resolve_path(string_of(*n, src, "normal"), base_dir, src, *n);
  if (auto* n = t->get("depth"))
    r.depth_path = resolve_path(string_of(*n, src, "depth"), base_dir, src, *n);
  if (auto* n = t->get("color"))
    r.color_path = resolve_path(string_of(*n, src, "color"), base_dir, src, *n);
  if (auto* n = t->get("convention")) {
    std::string c = string_of(*n, src, "convention");
    if (c != "height" && c != "depth")
      fail(src.at(*n),
           "'convention' must be \"height\" (1 = top) or \"depth\" (0 = top), got \"" + c + "\"");
    r.height_convention = c == "height";
  }
  if (auto* n = t->get("flip_green")) r.flip_green = number(*n, src, "flip_green") != 0;
  if (auto* n = t->get("normalize")) r.normalize = number(*n, src, "normalize") != 0;
  const std::string& sized = r.depth_path.empty() ? r.normal_path : r.depth_path;
  auto in = OIIO::ImageInput::open(sized);
  if (!in) fail(src.at(node), "cannot read image " + sized + ": " + OIIO::geterror());
  // Any aspect: a planar quad takes the map's (ReliefSourceDesc::aspect).
  r.native = {in->spec().width, in->spec().height};
  for (const std::string* p : {&r.normal_path, &r.depth_path, &r.color_path})
    if (!p->empty())
      canon["files"].push_back({fs::path(*p).filename().string(), hex64(file_hash(*p))});
  canon["convention"] = r.height_convention ? "height" : "depth";
  canon["flip_green"] = r.flip_green;
  canon["normalize"] = r.normalize;
  return r;
}

// base = "sphere" (generated kinds, the teapot) or a mesh file with uvs; segments = N.
// Only non-default values enter the canonical description, so planar cells keep their keys.
void parse_base(const toml::table& t, const Src& src, const std::string& base_dir, SceneDesc& s,
                json& canon) {
  if (auto* n = t.get("base")) {
    const std::string kind = string_of(*n, src, "base");
    static const std::set<std::string> generated = {"plane", "cube", "sphere", "torus", "teapot"};
    if (generated.count(kind)) {
      s.base.kind = kind;
    } else if (fs::path(kind).has_extension()) {
      s.base.kind = "file";
      s.base.path = resolve_path(kind, base_dir, src, *n);
      const TriangleMesh mesh = load_mesh(s.base.path);
      if (mesh.uvs.empty())
        fail(src.at(*n), "base mesh " + s.base.path +
                             " has no texture coordinates; a relief needs a uv mapping");
      canon["base_file"] =
          fs::path(s.base.path).filename().string() + ":" + hex64(file_hash(s.base.path));
    } else {
      fail(src.at(*n), "unknown base '" + kind +
                           "' (known: plane, cube, sphere, torus, teapot, or a mesh file path)");
    }
    if (s.base.curved()) canon["base"] = s.base.kind;
  }
  if (auto* n = t.get("segments")) {
    s.base.segments = positive_int(*n, src, "segments", 3, 4096);
    if (s.base.curved()) canon["segments"] = s.base.segments;
  }
  if (!s.base.curved()) return;
  if (s.proxy == Proxy::Box)
    fail(src.at(*t.get("base")), "scene '" + s.name +
                                     "': a curved base is drawn itself; proxy = \"box\" needs "
                                     "the planar base");
  if (!s.relief.mesh_path.empty())
    fail(src.at(*t.get("base")),
         "scene '" + s.name +
             "': a baked mesh relief needs the planar base (it is an object in "
             "its box)");
}

// objects = [{ shape = "sphere" | "cube" | "mesh.obj", center = [x, y, z], radius = r,
// albedo = [r, g, b] }]: plain triangle meshes standing in the scene (chapter 5, Figure 5.20).
void parse_objects(const toml::table& t, const Src& src, const std::string& base_dir, SceneDesc& s,
                   json& canon) {
  const toml::node* n = t.get("objects");
  if (!n) return;
  const toml::array* a = n->as_array();
  if (!a) fail(src.at(*n), "'objects' must be an array of tables, e.g. [{ shape = \"sphere\" }]");
  for (const toml::node& e : *a) {
    const toml::table* o = e.as_table();
    if (!o) fail(src.at(e), "each of 'objects' must be a table, e.g. { shape = \"sphere\" }");
    check_keys(*o, {"shape", "center", "radius", "albedo"}, src, "an object");
    SceneObject obj;
    if (auto* v = o->get("shape")) {
      obj.shape = string_of(*v, src, "shape");
      if (obj.shape != "sphere" && obj.shape != "cube")
        obj.shape = resolve_path(obj.shape, base_dir, src, *v);
    }
    if (auto* v = o->get("center")) obj.center = vec3_of(*v, src, "center");
    if (auto* v = o->get("radius")) {
      obj.radius = number(*v, src, "radius");
      if (!(obj.radius > 0) || !std::isfinite(obj.radius))
        fail(src.at(*v), "'radius' must be positive, got " + std::to_string(obj.radius));
    }
    if (auto* v = o->get("albedo")) obj.albedo = vec3_of(*v, src, "albedo");
    s.objects.push_back(obj);
    const bool file = obj.shape != "sphere" && obj.shape != "cube";
    const std::string shape_id =
        file ? fs::path(obj.shape).filename().string() + ":" + hex64(file_hash(obj.shape))
             : obj.shape;
    canon["objects"].push_back({shape_id, obj.center.x, obj.center.y, obj.center.z, obj.radius,
                                obj.albedo.x, obj.albedo.y, obj.albedo.z});
  }
  if (s.relief.reverse_cop > 1)
    fail(src.at(*n), "scene '" + s.name + "': objects are not supported with reverse_perspective");
}

SceneDesc parse_scene(const toml::table& t, const Src& src, const std::string& base_dir,
                      const toml::node& node, json& canon) {
  check_keys(t, {"name",        "relief",
                 "base",        "segments",
                 "objects",     "proxy",
                 "truth",       "floor",
                 "size",        "tile",
                 "depth",       "quantize",
                 "effects",     "light",
                 "fov",         "distance",
                 "shadow_bias", "ambient",
                 "diffuse",     "specular",
                 "shininess",   "shadow_intensity",
                 "framing"},
             src, "[[scene]]");
  SceneDesc s;
  if (!t.contains("name")) fail(src.at(node), "[[scene]] needs a 'name'");
  s.name = string_of(*t.get("name"), src, "name");
  if (!t.contains("relief")) fail(src.at(node), "scene '" + s.name + "' needs a 'relief'");
  s.relief = parse_relief(*t.get("relief"), src, base_dir, canon["relief"]);
  auto positive = [&](const char* key, double& out) {
    if (auto* n = t.get(key)) {
      out = number(*n, src, key);
      if (!(out > 0) || !std::isfinite(out))
        fail(src.at(*n), std::string("'") + key + "' must be positive, got " + std::to_string(out));
    }
  };
  positive("size", s.size);
  if (!s.relief.mesh_path.empty()) {
    // A baked mesh keeps its proportions: the relief depth follows from the footprint.
    if (t.contains("depth"))
      fail(src.at(*t.get("depth")),
           "scene '" + s.name + "': 'depth' comes from the mesh's proportions; set 'size' instead");
    if (t.contains("tile"))
      fail(src.at(*t.get("tile")), "scene '" + s.name + "': a baked mesh is not tiled");
    const TriangleMesh mesh = load_mesh(s.relief.mesh_path);
    const BakeFrame frame = bake_frame(mesh, s.relief.mesh_up);
    s.depth = s.size * frame.height / frame.side;
  }
  positive("tile", s.tile);
  positive("depth", s.depth);
  positive("fov", s.fov_deg);
  positive("shininess", s.material.shininess);
  if (s.fov_deg >= 170) fail(src.at(*t.get("fov")), "'fov' must be below 170 degrees");
  if (auto* n = t.get("distance")) {
    s.distance = number(*n, src, "distance");
    if (s.distance < 0) fail(src.at(*n), "'distance' must be >= 0 (0 = fit the quad)");
  }
  if (auto* n = t.get("shadow_bias")) s.shadow_bias = number(*n, src, "shadow_bias");
  if (auto* n = t.get("shadow_intensity"))
    s.material.shadow_intensity = number(*n, src, "shadow_intensity");
  if (auto* n = t.get("quantize")) {
    if (!n->is_boolean()) fail(src.at(*n), "'quantize' must be true (8-bit) or false (float)");
    s.quantize = n->value<bool>().value();
  }
  if (auto* n = t.get("light")) s.light_position = vec3_of(*n, src, "light");
  if (auto* n = t.get("truth")) {
    const std::string level = string_of(*n, src, "truth");
    if (level != "sampled" && level != "mesh")
      fail(src.at(*n),
           "'truth' must be \"sampled\" (the map's heightfield) or \"mesh\" (the baked mesh)");
    s.truth = level == "mesh" ? TruthLevel::Mesh : TruthLevel::Sampled;
    if (s.truth == TruthLevel::Mesh && s.relief.mesh_path.empty())
      fail(src.at(*n), "truth = \"mesh\" needs a mesh relief (relief = { mesh = \"...\" })");
  }
  s.empty_floor = !s.relief.mesh_path.empty();
  if (auto* n = t.get("floor")) {
    const std::string f = string_of(*n, src, "floor");
    if (f != "solid" && f != "empty")
      fail(src.at(*n), "'floor' must be \"solid\" or \"empty\" (default: empty for baked meshes)");
    s.empty_floor = f == "empty";
  }
  if (auto* n = t.get("proxy")) {
    const std::string p = string_of(*n, src, "proxy");
    if (p != "base" && p != "box")
      fail(src.at(*n),
           "'proxy' must be \"base\" (draw the base surface) or \"box\" (draw the "
           "relief's bounding box), got \"" +
               p + "\"");
    s.proxy = p == "box" ? Proxy::Box : Proxy::Base;
  }
  if (auto* n = t.get("ambient")) s.material.ambient = vec3_of(*n, src, "ambient");
  if (auto* n = t.get("diffuse")) s.material.diffuse = vec3_of(*n, src, "diffuse");
  if (auto* n = t.get("specular")) s.material.specular = vec3_of(*n, src, "specular");
  if (auto* n = t.get("effects")) {
    for (const std::string& e : string_list(*n, src, "effects")) {
      auto effect = parse_effect(e);
      if (!effect) {
        std::string known;
        for (Effect k : all_effects()) known += (known.empty() ? "" : ", ") + effect_name(k);
        fail(src.at(*n), "unknown effect '" + e + "' (known: " + known + ")");
      }
      s.effects.add(*effect);
    }
  }
  parse_base(t, src, base_dir, s, canon);
  parse_objects(t, src, base_dir, s, canon);
  canon["name"] = s.name;
  canon["proxy"] = s.proxy == Proxy::Box ? "box" : "base";
  canon["truth"] = s.truth == TruthLevel::Mesh ? "mesh" : "sampled";
  canon["floor"] = s.empty_floor ? "empty" : "solid";
  s.projection.cop = s.relief.reverse_cop;
  if (s.projection.active() && s.proxy != Proxy::Box)
    fail(src.at(node), "scene '" + s.name +
                           "': reverse_perspective needs proxy = \"box\" (the frustum is drawn)");
  if (s.projection.active() && s.effects.has(Effect::SelfShadow))
    fail(src.at(node),
         "scene '" + s.name + "': self_shadow is not supported with reverse_perspective yet");
  if (s.truth == TruthLevel::Mesh && s.proxy != Proxy::Box)
    fail(src.at(node),
         "scene '" + s.name +
             "': truth = \"mesh\" needs proxy = \"box\" (the mesh is an object in its box)");
  // Framing: fill by default where it applies (a planar quad drawn itself, no stated camera
  // distance); the quad is lengthened for the sweep's views once they are known.
  const bool can_fill =
      !s.base.curved() && s.proxy == Proxy::Base && s.distance == 0 && s.relief.mesh_path.empty();
  s.framing = can_fill ? Framing::Fill : Framing::Fit;
  if (auto* n = t.get("framing")) {
    const std::string f = string_of(*n, src, "framing");
    if (f != "fill" && f != "fit")
      fail(src.at(*n),
           "'framing' must be \"fill\" (the relief fills the viewport) or \"fit\" "
           "(the whole quad in view), got \"" +
               f + "\"");
    if (f == "fill" && !can_fill)
      fail(src.at(*n), "scene '" + s.name +
                           "': framing = \"fill\" needs the planar base drawn itself (no box "
                           "proxy, no curved base, no baked mesh) and no 'distance'");
    s.framing = f == "fill" ? Framing::Fill : Framing::Fit;
  }
  canon["framing"] = s.framing == Framing::Fill ? "fill" : "fit";
  canon["size"] = s.size;
  canon["tile"] = s.tile;
  canon["depth"] = s.depth;
  canon["quantize"] = s.quantize;
  canon["effects"] = join_effects(s.effects);
  canon["light"] = {s.light_position.x, s.light_position.y, s.light_position.z};
  canon["fov"] = s.fov_deg;
  canon["distance"] = s.distance;
  canon["shadow_bias"] = s.shadow_bias;
  const Material& m = s.material;
  canon["material"] = {m.ambient.x,  m.ambient.y, m.ambient.z,       m.diffuse.x,
                       m.diffuse.y,  m.diffuse.z, m.specular.x,      m.specular.y,
                       m.specular.z, m.shininess, m.shadow_intensity};
  return s;
}

TechniqueSweep parse_technique(const toml::table& t, const Src& src, const toml::node& node) {
  TechniqueSweep ts;
  ts.where = src.at(node);
  if (!t.contains("name")) fail(ts.where, "[[technique]] needs a 'name'");
  ts.name = string_of(*t.get("name"), src, "name");
  const TechniqueEntry* entry = TechniqueRegistry::instance().find(ts.name);
  if (!entry) {
    std::string known;
    for (const auto& n : TechniqueRegistry::instance().names())
      known += (known.empty() ? "" : ", ") + n;
    fail(src.at(*t.get("name")), "unknown technique '" + ts.name + "' (known: " + known + ")");
  }
  for (auto&& [k, v] : t) {
    const std::string key(k.str());
    if (key == "name") continue;
    if (key == "scenes") {
      ts.scenes = string_list(v, src, key);
      continue;
    }
    const ParamSpec* spec = nullptr;
    for (const ParamSpec& p : entry->info.params)
      if (p.name == key) spec = &p;
    if (!spec) {
      std::string known = "scenes";
      for (const ParamSpec& p : entry->info.params) known += ", " + p.name;
      fail(src.at(v),
           "technique '" + ts.name + "' has no parameter '" + key + "' (known: " + known + ")");
    }
    std::vector<double> values = number_list(v, src, key);
    for (double value : values)
      check_param_value(*spec, value, src.at(v) + ": technique '" + ts.name + "'");
    ts.param_lists[key] = values;
  }
  return ts;
}

}  // namespace

int resolve_texture_res(const SceneDesc& scene, int texture_res) {
  return texture_res > 0 ? texture_res : scene.relief.native.longer();
}

SweepConfig parse_sweep_config(const std::string& text, const std::string& source_name,
                               const std::string& base_dir) {
  Src src{source_name};
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    throw ConfigError(source_name + ":" + std::to_string(e.source().begin.line) +
                      ": TOML syntax error: " + std::string(e.description()));
  }
  check_keys(root, {"sweep", "scene", "technique", "table", "plot"}, src, "the top level");
  SweepConfig c;
  c.source = source_name;
  json canon;

  // [sweep]
  std::vector<double> elevations = {45}, azimuths = {0};
  if (auto* n = root.get("sweep")) {
    const toml::table* t = n->as_table();
    if (!t) fail(src.at(*n), "[sweep] must be a table");
    check_keys(*t,
               {"name", "elevations", "azimuths", "views", "viewports", "texture_res", "frames",
                "warmup", "heat_map_scale", "truth_tolerance", "images", "gbuffers"},
               src, "[sweep]");
    if (auto* v = t->get("name")) c.name = string_of(*v, src, "name");
    if (auto* v = t->get("elevations")) elevations = number_list(*v, src, "elevations");
    if (auto* v = t->get("azimuths")) azimuths = number_list(*v, src, "azimuths");
    for (double e : elevations)
      if (!(e > 0 && e <= 90))
        fail(src.at(*t->get("elevations")),
             "elevations must be in (0, 90] degrees, got " + std::to_string(e));
    if (auto* v = t->get("views")) {
      const toml::array* a = v->as_array();
      if (!a) fail(src.at(*v), "'views' must be an array of [elevation, azimuth] pairs");
      for (const toml::node& e : *a) {
        std::vector<double> pair = number_list(e, src, "views");
        if (pair.size() != 2 || !(pair[0] > 0 && pair[0] <= 90))
          fail(src.at(e), "each view must be [elevation in (0, 90], azimuth]");
        c.views.push_back({pair[0], pair[1]});
      }
    }
    if (auto* v = t->get("viewports")) {
      const toml::array* a = v->as_array();
      if (!a)
        fail(src.at(*v), "'viewports' must be an array of sizes (256) or [width, height] pairs");
      for (const toml::node& e : *a) {
        std::vector<double> wh = number_list(e, src, "viewports");
        if (wh.size() == 1) wh.push_back(wh[0]);
        if (wh.size() != 2 || wh[0] < 1 || wh[1] < 1 || wh[0] > 8192 || wh[1] > 8192 ||
            wh[0] != std::floor(wh[0]) || wh[1] != std::floor(wh[1]))
          fail(src.at(e), "each viewport must be a size or [width, height] in 1..8192");
        c.viewports.push_back({int(wh[0]), int(wh[1])});
      }
    }
    if (auto* v = t->get("texture_res")) {
      for (double r : number_list(*v, src, "texture_res")) {
        if (r != std::floor(r) || r < 0 || r > 8192 || r == 1)
          fail(src.at(*v), "texture_res must be 0 (native) or an integer in [2, 8192], got " +
                               std::to_string(r));
        c.texture_res.push_back(int(r));
      }
    }
    if (auto* v = t->get("frames")) c.frames = positive_int(*v, src, "frames", 1, 1000);
    if (auto* v = t->get("warmup")) c.warmup = positive_int(*v, src, "warmup", 0, 100);
    if (auto* v = t->get("heat_map_scale")) {
      c.heat_map_scale = number(*v, src, "heat_map_scale");
      if (!(c.heat_map_scale > 0)) fail(src.at(*v), "'heat_map_scale' must be positive");
    }
    if (auto* v = t->get("truth_tolerance")) {
      c.truth_tolerance = number(*v, src, "truth_tolerance");
      if (!(c.truth_tolerance > 0 && c.truth_tolerance < 1))
        fail(src.at(*v), "'truth_tolerance' must be in (0, 1)");
    }
    if (auto* v = t->get("images")) {
      if (!v->is_boolean()) fail(src.at(*v), "'images' must be true or false");
      c.write_images = v->value<bool>().value();
    }
    if (auto* v = t->get("gbuffers")) {
      if (!v->is_boolean()) fail(src.at(*v), "'gbuffers' must be true or false");
      c.write_gbuffers = v->value<bool>().value();
    }
  }
  if (c.views.empty())
    for (double e : elevations)
      for (double a : azimuths) c.views.push_back({e, a});
  if (c.viewports.empty()) c.viewports.push_back({256, 256});
  if (c.texture_res.empty()) c.texture_res.push_back(0);

  // [[scene]]
  const toml::array* scenes = root.get("scene") ? root.get("scene")->as_array() : nullptr;
  if (!scenes || scenes->empty()) fail(source_name, "no [[scene]] given");
  std::set<std::string> scene_names;
  for (const toml::node& n : *scenes) {
    const toml::table* t = n.as_table();
    if (!t) fail(src.at(n), "[[scene]] must be a table");
    json sc;
    c.scenes.push_back(parse_scene(*t, src, base_dir, n, sc));
    SceneDesc& scene = c.scenes.back();
    if (scene.framing == Framing::Fill) {
      // Lengthen the quad (whole tiles more) for the grazing-est view of the sweep.
      double min_el = 90, max_aspect = 0;
      for (const View& v : c.views) min_el = std::min(min_el, v.elevation_deg);
      for (const auto& [w, h] : c.viewports) max_aspect = std::max(max_aspect, double(w) / h);
      apply_fill_framing(scene, min_el, max_aspect);
      sc["size"] = scene.size;
      sc["tile"] = scene.tile;
    }
    if (!scene_names.insert(c.scenes.back().name).second)
      fail(src.at(n), "duplicate scene name '" + c.scenes.back().name + "'");
    canon["scenes"][c.scenes.back().name] = sc;
    c.scene_canonical[c.scenes.back().name] = sc.dump();
  }

  // [[technique]]
  const toml::array* techniques =
      root.get("technique") ? root.get("technique")->as_array() : nullptr;
  if (!techniques || techniques->empty()) fail(source_name, "no [[technique]] given");
  for (const toml::node& n : *techniques) {
    const toml::table* t = n.as_table();
    if (!t) fail(src.at(n), "[[technique]] must be a table");
    TechniqueSweep ts = parse_technique(*t, src, n);
    for (const std::string& s : ts.scenes)
      if (!scene_names.count(s))
        fail(ts.where, "technique '" + ts.name + "' names unknown scene '" + s + "'");
    // Effects: every scene this technique runs on must ask only for effects it simulates.
    const TechniqueInfo& tinfo = TechniqueRegistry::instance().find(ts.name)->info;
    const EffectSet supported = tinfo.effects;
    for (const SceneDesc& s : c.scenes) {
      const bool runs = ts.scenes.empty() ||
                        std::find(ts.scenes.begin(), ts.scenes.end(), s.name) != ts.scenes.end();
      if (runs && !supported.contains_all(s.effects))
        fail(ts.where, "technique '" + ts.name + "' does not support effect(s) " +
                           join_effects(supported.missing_from(s.effects)) +
                           " requested by scene '" + s.name +
                           "' (it supports: " + join_effects(supported) +
                           "); restrict it with scenes = [...] or drop the effect");
      if (runs && s.proxy == Proxy::Box && !tinfo.box_proxy)
        fail(ts.where, "technique '" + ts.name + "' cannot render scene '" + s.name +
                           "' with proxy = \"box\" (it only shades the base surface); restrict "
                           "it with scenes = [...]");
    }
    c.techniques.push_back(ts);
  }

  // [[table]]
  std::set<std::string> fields = {"technique",   "scene",       "elevation_deg",
                                  "azimuth_deg", "texture_res", "viewport"};
  for (const auto& name : TechniqueRegistry::instance().names())
    for (const ParamSpec& p : TechniqueRegistry::instance().find(name)->info.params)
      fields.insert(p.name);
  if (auto* n = root.get("table")) {
    const toml::array* tables = n->as_array();
    if (!tables) fail(src.at(*n), "tables are given as [[table]]");
    for (const toml::node& tn : *tables) {
      const toml::table* t = tn.as_table();
      if (!t) fail(src.at(tn), "[[table]] must be a table");
      check_keys(*t, {"file", "title", "rows", "columns", "values"}, src, "[[table]]");
      TableSpec spec;
      spec.file =
          c.tables.empty() ? "table.md" : "table-" + std::to_string(c.tables.size() + 1) + ".md";
      if (auto* v = t->get("file")) spec.file = string_of(*v, src, "file");
      if (spec.file.find('/') != std::string::npos || spec.file.find("..") != std::string::npos)
        fail(src.at(*t->get("file")), "table 'file' must be a plain file name");
      if (auto* v = t->get("title")) spec.title = string_of(*v, src, "title");
      if (auto* v = t->get("rows")) spec.rows = string_list(*v, src, "rows");
      if (auto* v = t->get("columns")) spec.columns = string_list(*v, src, "columns");
      if (auto* v = t->get("values")) spec.values = string_list(*v, src, "values");
      if (spec.values.empty()) fail(src.at(tn), "[[table]] needs 'values' (metric names)");
      for (const std::string& v : spec.values)
        if (!is_measured(v))
          fail(src.at(tn),
               "[[table]] value '" + v + "' is not a measured column (" + measured_list() + ")");
      for (const auto* list : {&spec.rows, &spec.columns})
        for (const std::string& f : *list)
          if (!fields.count(f))
            fail(src.at(tn), "[[table]] field '" + f + "' is not a sweep field or parameter");
      c.tables.push_back(spec);
    }
  }
  if (c.tables.empty()) {
    TableSpec t;
    t.rows = {"scene", "elevation_deg", "technique"};
    for (const auto& ts : c.techniques)
      for (const auto& [p, v] : ts.param_lists)
        if (std::find(t.rows.begin(), t.rows.end(), p) == t.rows.end()) t.rows.push_back(p);
    t.values = {"wrong_pct", "pos_err_rmse", "artifact_pct", "psnr_db", "fetches_mean", "frame_ms"};
    c.tables.push_back(t);
  }

  // [[plot]]
  if (auto* n = root.get("plot")) {
    const toml::array* plots = n->as_array();
    if (!plots) fail(src.at(*n), "plots are given as [[plot]]");
    for (const toml::node& pn : *plots) {
      const toml::table* t = pn.as_table();
      if (!t) fail(src.at(pn), "[[plot]] must be a table");
      check_keys(*t, {"x", "y", "group", "log_y"}, src, "[[plot]]");
      PlotSpec p;
      if (auto* v = t->get("x")) p.x = string_of(*v, src, "x");
      if (auto* v = t->get("y")) p.y = string_of(*v, src, "y");
      if (auto* v = t->get("group")) p.group = string_list(*v, src, "group");
      if (auto* v = t->get("log_y")) p.log_y = number(*v, src, "log_y") != 0;
      for (const std::string& m : {p.x, p.y})
        if (!is_measured(m))
          fail(src.at(pn),
               "[[plot]] axis '" + m + "' is not a measured column (" + measured_list() + ")");
      for (const std::string& f : p.group)
        if (!fields.count(f))
          fail(src.at(pn), "[[plot]] group field '" + f + "' is not a sweep field or parameter");
      c.plots.push_back(p);
    }
  }
  if (c.plots.empty()) c.plots.push_back(PlotSpec{});

  canon["frames"] = c.frames;
  canon["warmup"] = c.warmup;
  canon["truth_tolerance"] = c.truth_tolerance;
  c.canonical = canon.dump();
  return c;
}

SweepConfig load_sweep_config(const std::string& path) {
  if (!fs::exists(path)) throw ConfigError(path + ": config file not found");
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot read config file");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string dir = fs::absolute(path).parent_path().string();
  return parse_sweep_config(ss.str(), path, dir);
}

SweepConfig default_sweep_config() {
  const auto& files = embedded_files();
  auto it = files.find("configs/default.toml");
  if (it == files.end()) throw ConfigError("built-in default config missing from the build");
  return parse_sweep_config(it->second, "<built-in configs/default.toml>",
                            std::string(RELIEFLAB_SOURCE_DIR) + "/configs");
}

}  // namespace rl
