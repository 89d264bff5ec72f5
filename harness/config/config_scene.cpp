#include "config/config_scene.h"

#include <cmath>
#include <filesystem>
#include <set>
#include <utility>

#include "config/config_cube.h"
#include "config/config_effects.h"
#include "config/config_meta.h"
#include "config/config_relief.h"
#include "core/error.h"

namespace rl {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// base = "sphere" (generated kinds, the teapot) or a mesh file with uvs; segments = N.
// Only non-default values enter the canonical description, so planar cells keep their keys.
void parse_base(const toml::table& t, const Src& src, const std::string& base_dir, SceneDesc& s,
                json& canon, SceneSites& sites) {
  if (auto* n = t.get("base")) {
    const std::string kind = string_of(*n, src, "base");
    static const std::set<std::string> generated = {"plane", "cube", "sphere", "torus", "teapot"};
    if (generated.count(kind)) {
      s.base.kind = kind;
    } else if (fs::path(kind).has_extension()) {
      s.base.kind = "file";
      s.base.path = resolve_path(kind, base_dir, src, *n);
      sites.base = src.at(*n);  // its uvs are checked by read_scene_files()
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
  if (!s.relief.mesh_path.empty() && s.relief.layers == 0)
    fail(src.at(*t.get("base")),
         "scene '" + s.name +
             "': a baked mesh relief needs the planar base (it is an object in its box), "
             "unless it is baked into layers (layers = N: a pattern repeated over the base)");
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
    if (auto* v = o->get("center")) obj.center = vec3_in(*v, src, "center", -1e3, 1e3);
    if (auto* v = o->get("radius")) obj.radius = number_in(*v, src, "radius", 1e-4, 1e3);
    if (auto* v = o->get("albedo")) obj.albedo = vec3_in(*v, src, "albedo", 0, 1);
    s.objects.push_back(obj);
    // A file shape's entry becomes "name:hash" in read_scene_files().
    canon["objects"].push_back({obj.shape, obj.center.x, obj.center.y, obj.center.z, obj.radius,
                                obj.albedo.x, obj.albedo.y, obj.albedo.z});
  }
  if (s.relief.reverse_cop > 1)
    fail(src.at(*n), "scene '" + s.name + "': objects are not supported with reverse_perspective");
}

}  // namespace

namespace {

// What the scene is measured against ('truth', default by its relief) and at what map size
// ('truth_resolution').
void parse_truth_level(const toml::table& t, const Src& src, SceneDesc& s, nlohmann::json& canon) {
  if (auto* n = t.get("truth")) {
    const std::string level = string_of(*n, src, "truth");
    if (level != "sampled" && level != "mesh" && level != "layers" && level != "cells")
      fail(src.at(*n),
           "'truth' must be \"sampled\" (the map's heightfield), \"mesh\" (the mesh or pattern "
           "the map was baked from), \"layers\" (a multilayer map's own layers) or \"cells\" "
           "(the surface a cell complex's distance maps encode)");
    s.truth = level == "mesh"     ? TruthLevel::Mesh
              : level == "layers" ? TruthLevel::Layers
              : level == "cells"  ? TruthLevel::Cells
                                  : TruthLevel::Sampled;
    if (s.truth == TruthLevel::Cells && !s.cell_complex())
      fail(src.at(*n), "truth = \"cells\" needs a cell-complex relief (relief = { cells = ... })");
    if (s.truth == TruthLevel::Mesh && s.relief.mesh_path.empty() && !s.relief.pattern_mesh())
      fail(src.at(*n),
           "truth = \"mesh\" needs a mesh relief (relief = { mesh = \"...\" }) or "
           "a pattern (weave, helix)");
    if (s.truth == TruthLevel::Layers && s.relief.layers == 0)
      fail(src.at(*n), "truth = \"layers\" needs a multilayer relief (a pattern, or 'layers')");
    if (s.truth == TruthLevel::Sampled && s.relief.layers > 0)
      fail(src.at(*n),
           "a multilayer relief has no single heightfield to sample; its truths are "
           "\"mesh\" (what it was baked from) and \"layers\" (its own layers)");
  } else if (s.relief.layers > 0 || s.in_cube()) {
    s.truth = TruthLevel::Mesh;  // measured against the geometry it stands for
  }
  if (auto* n = t.get("truth_resolution")) {
    if (s.truth != TruthLevel::Sampled || !s.relief.mesh_path.empty())
      fail(src.at(*n), "scene '" + s.name +
                           "': 'truth_resolution' applies to the sampled truth of a heightfield "
                           "(the map at another resolution)");
    s.truth_texture_res = positive_int(*n, src, "truth_resolution", 2, 8192);
    canon["truth_resolution"] = s.truth_texture_res;
  }
}

// color_resolution: the colour map at its own resolution (Baboud & Decoret, Section 4.3), and
// truth_color_resolution: the truth's; read after the relief and the meta-relief they must not
// be.
void parse_color_resolution(const toml::table& t, const Src& src, SceneDesc& s,
                            nlohmann::json& canon) {
  const std::pair<const char*, int*> keys[] = {
      {"color_resolution", &s.color_texture_res},
      {"truth_color_resolution", &s.truth_color_texture_res}};
  for (const auto& [key, field] : keys) {
    const toml::node* n = t.get(key);
    if (!n) continue;
    if (s.relief.layers > 0 || !s.relief.mesh_path.empty() || s.cell_complex() ||
        s.relief.pattern_mesh() || s.meta.active() || s.truth != TruthLevel::Sampled)
      fail(src.at(*n), "scene '" + s.name + "': '" + key +
                           "' applies to a heightfield from images or a procedure, measured "
                           "against its sampled truth (a meta-relief has its own "
                           "color_resolution, in meta_relief)");
    *field = positive_int(*n, src, key, 2, 8192);
    canon[key] = *field;
  }
}

// Combinations of keys that are not built (each refused naming the scene).
void check_scene_combinations(const SceneDesc& s, const Src& src, const toml::node& node) {
  if (s.projection.active() && s.proxy != Proxy::Box)
    fail(src.at(node), "scene '" + s.name +
                           "': reverse_perspective needs proxy = \"box\" (the frustum is drawn)");
  if (s.clip_frustum && (!s.projection.active() || s.tile != 1.0))
    fail(src.at(node), "scene '" + s.name +
                           "': clip_frustum cuts a reverse-perspective frustum (relief key "
                           "reverse_perspective, tile 1) to the relief's bounding box");
  if (s.projection.active() && s.effects.has(Effect::SelfShadow))
    fail(src.at(node),
         "scene '" + s.name + "': self_shadow is not supported with reverse_perspective yet");
  if (s.relief.layers > 0) {
    // Not built: layers in a box proxy (its truth would be the mesh clipped to the box), and a
    // floor under a pattern on a curved base or an impostor (what shows through is behind).
    const std::string no = "scene '" + s.name + "': a multilayer relief ";
    if (s.proxy == Proxy::Box)
      fail(src.at(node), no + "is drawn on its base; proxy = \"box\" "
                              "is not supported yet");
    if (s.base.curved() && s.truth == TruthLevel::Layers)
      fail(src.at(node), no + "on a curved base has the pattern mesh as its truth, not "
                              "\"layers\"");
    if (!s.empty_floor && s.impostor())
      fail(src.at(node), no + "as an impostor has an empty floor (its gaps show what lies "
                              "behind); floor = \"solid\" applies on a base");
  }
  if (s.truth == TruthLevel::Mesh && !s.relief.mesh_path.empty() && !s.impostor() &&
      s.proxy != Proxy::Box && !s.base.curved())
    fail(src.at(node),
         "scene '" + s.name +
             "': truth = \"mesh\" needs proxy = \"box\" (the mesh is an object in its box)");
}

void parse_framing(const toml::table& t, const Src& src, SceneDesc& s) {
  // A fill-framed quad grows with the views (many tiles at grazing ones), where scene_shadows'
  // shadow map must hold it whole.
  const bool can_fill = !s.base.curved() && s.proxy == Proxy::Base && s.distance == 0 &&
                        s.relief.mesh_path.empty() && !s.effects.has(Effect::SceneShadows);
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
                           "proxy, no curved base, no baked mesh), no 'distance' and no "
                           "scene_shadows (its shadow map holds the quad whole)");
    s.framing = f == "fill" ? Framing::Fill : Framing::Fit;
  }
}

// The rest of the scene's canonical description (what keys its cells).
void describe_scene(const SceneDesc& s, nlohmann::json& canon) {
  canon["framing"] = s.framing == Framing::Fill ? "fill" : "fit";
  canon["size"] = s.size;
  canon["tile"] = s.tile;
  canon["depth"] = s.depth;
  canon["quantize"] = s.quantize;
  if (s.clip_frustum) canon["clip_frustum"] = true;  // absent: keys as before the option
  canon["effects"] = join_effects(s.effects);
  canon["light"] = {s.light_position.x, s.light_position.y, s.light_position.z};
  canon["fov"] = s.fov_deg;
  canon["distance"] = s.distance;
  canon["shadow_bias"] = s.shadow_bias;
  const Material& m = s.material;
  canon["material"] = {m.ambient.x,  m.ambient.y, m.ambient.z,       m.diffuse.x,
                       m.diffuse.y,  m.diffuse.z, m.specular.x,      m.specular.y,
                       m.specular.z, m.shininess, m.shadow_intensity};
}

// Every key a [[scene]] table may hold.
const std::set<std::string> kSceneKeys = {
    "name",
    "relief",
    "base",
    "segments",
    "objects",
    "proxy",
    "truth",
    "floor",
    "floor_color",
    "size",
    "tile",
    "depth",
    "quantize",
    "clip_frustum",
    "effects",
    "light",
    "fov",
    "distance",
    "shadow_bias",
    "shadow_map",
    "ambient",
    "diffuse",
    "specular",
    "shininess",
    "shadow_intensity",
    "framing",
    "ambient_occlusion",
    "meta_relief",
    "truth_resolution",
    "color_resolution",
    "truth_color_resolution",
};

// The scene's numbers, each within a stated range (hostile input, first round): a value outside it
// is a mistake, not a scene (size 1e-300, depth 1e30, fov 1e-30 all rendered nothing and were
// published).
void parse_numbers(const toml::table& t, const Src& src, SceneDesc& s) {
  auto in_range = [&](const char* key, double& out, double lo, double hi) {
    if (auto* n = t.get(key)) out = number_in(*n, src, key, lo, hi);
  };
  in_range("size", s.size, 1e-3, 1e3);
  // On a curved base a mesh's layers repeat as a pattern does: its tile and depth are the
  // scene's (the object stretches with the tile).
  const toml::node* base = t.get("base");
  const bool curved = base && base->value_or(std::string("plane")) != "plane";
  if (!s.relief.mesh_path.empty() && !curved) {
    // A baked mesh keeps its proportions: the relief depth follows from the footprint.
    if (t.contains("depth"))
      fail(src.at(*t.get("depth")),
           "scene '" + s.name + "': 'depth' comes from the mesh's proportions; set 'size' instead");
    if (t.contains("tile"))
      fail(src.at(*t.get("tile")), "scene '" + s.name + "': a baked mesh is not tiled");
    // read_scene_files() sets the depth from the mesh's proportions.
  }
  in_range("tile", s.tile, 1e-3, 1e3);
  in_range("depth", s.depth, 1e-4, 10);
  in_range("fov", s.fov_deg, 1, 160);
  in_range("shininess", s.material.shininess, 1e-3, 1e4);
  in_range("distance", s.distance, 0, 1e3);  // 0 = fit the quad
  in_range("shadow_bias", s.shadow_bias, 0, 1);
  in_range("shadow_intensity", s.material.shadow_intensity, 0, 1);
  if (auto* n = t.get("clip_frustum")) {
    if (!n->is_boolean())
      fail(src.at(*n),
           "'clip_frustum' must be true (the frustum cut to the relief's bounding "
           "box, Baboud & Decoret 2006, Section 4.1) or false");
    s.clip_frustum = n->value<bool>().value();
  }
  if (auto* n = t.get("quantize")) {
    if (!n->is_boolean()) fail(src.at(*n), "'quantize' must be true (8-bit) or false (float)");
    s.quantize = n->value<bool>().value();
  }
  if (auto* n = t.get("light")) s.light_position = vec3_in(*n, src, "light", -1e3, 1e3);
}

// floor = "solid" | "empty" (default: empty for baked meshes); proxy = "base" | "box".
void parse_floor_and_proxy(const toml::table& t, const Src& src, SceneDesc& s) {
  s.empty_floor = !s.relief.mesh_path.empty() || s.relief.pattern_mesh();
  if (auto* n = t.get("floor")) {
    const std::string f = string_of(*n, src, "floor");
    if (f != "solid" && f != "empty")
      fail(src.at(*n), "'floor' must be \"solid\" or \"empty\" (default: empty for baked meshes)");
    s.empty_floor = f == "empty";
  }
  if (auto* n = t.get("floor_color")) {
    if (s.empty_floor || s.relief.layers == 0)
      fail(src.at(*n), "'floor_color' colours a layered relief's solid floor (floor = \"solid\")");
    s.floor_color = vec3_in(*n, src, "floor_color", 0, 1);
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
}

// The Phong material's colours and the effects the scene asks for.
void parse_material_and_effects(const toml::table& t, const Src& src, SceneDesc& s) {
  if (auto* n = t.get("ambient")) s.material.ambient = vec3_in(*n, src, "ambient", 0, 1);
  if (auto* n = t.get("diffuse")) s.material.diffuse = vec3_in(*n, src, "diffuse", 0, 1);
  if (auto* n = t.get("specular")) s.material.specular = vec3_in(*n, src, "specular", 0, 1);
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
}

}  // namespace

ParsedScene parse_scene(const toml::table& t, const Src& src, const std::string& base_dir,
                        const toml::node& node) {
  ParsedScene parsed;
  json& canon = parsed.canon;
  check_keys(t, kSceneKeys, src, "[[scene]]");
  SceneDesc& s = parsed.scene;
  parsed.sites.scene = src.at(node);
  parsed.sites.relief = t.get("relief") ? src.at(*t.get("relief")) : parsed.sites.scene;
  if (!t.contains("name")) fail(src.at(node), "[[scene]] needs a 'name'");
  s.name = plain_name(*t.get("name"), src, "name");
  if (!t.contains("relief")) fail(src.at(node), "scene '" + s.name + "' needs a 'relief'");
  s.relief = parse_relief(*t.get("relief"), src, base_dir, canon["relief"]);
  parse_numbers(t, src, s);
  parse_truth_level(t, src, s, canon);
  parse_floor_and_proxy(t, src, s);
  parse_material_and_effects(t, src, s);
  parse_base(t, src, base_dir, s, canon, parsed.sites);
  parse_objects(t, src, base_dir, s, canon);
  parse_effect_options(t, src, node, s, canon);
  parse_scene_shadows(t, src, node, s, canon);
  parse_meta_relief(t, src, base_dir, node, s, canon);
  parse_color_resolution(t, src, s, canon);
  apply_in_cube_scene(t, src, node, s);
  canon["name"] = s.name;
  canon["proxy"] = s.proxy == Proxy::Box ? "box" : "base";
  canon["truth"] = truth_level_name(s.truth);
  canon["floor"] = s.empty_floor ? "empty" : "solid";
  if (t.contains("floor_color"))
    canon["floor_color"] = {s.floor_color.r, s.floor_color.g, s.floor_color.b};
  // A heightfield object's faces carry their own reverse perspective; its cube is affine.
  if (!s.heightfield_object()) s.projection.cop = s.relief.reverse_cop;
  check_scene_combinations(s, src, node);
  // Framing: fill by default where it applies (a planar quad drawn itself, no stated camera
  // distance); the quad is lengthened for the sweep's views once they are known.
  parse_framing(t, src, s);
  describe_scene(s, canon);
  return parsed;
}

}  // namespace rl
