#include "config/config_relief.h"

#include <cmath>

#include "config/config_cells.h"
#include "core/error.h"
#include "relief/pattern_mesh.h"
#include "relief/procedural.h"

namespace rl {
namespace {

// layers = N (1 to 8): a mesh or pattern baked into N depth layers per texel.
void parse_layers(const toml::table& t, const Src& src, ReliefSourceDesc& r,
                  nlohmann::json& canon) {
  if (auto* n = t.get("layers")) {
    r.layers = positive_int(*n, src, "layers", 1, LayerStack::kMaxLayers);
    canon["layers"] = r.layers;
  }
}

// relief = { mesh = "file", up, resolution, reverse_perspective, layers, faces,
// open_surface_gap, three_views }.
void parse_mesh_relief(const toml::table& t, const toml::node& node, const Src& src,
                       const std::string& base_dir, ReliefSourceDesc& r, nlohmann::json& canon) {
  for (const char* k : {"color", "convention", "flip_green", "normalize", "nodata", "options"})
    if (t.contains(k))
      fail(src.at(node), std::string("'") + k + "' does not apply to a mesh relief");
  const toml::node& mn = *t.get("mesh");
  r.mesh_path = resolve_path(string_of(mn, src, "mesh"), base_dir, src, mn);
  if (auto* n = t.get("up")) {
    const std::string up = string_of(*n, src, "up");
    if (up != "x" && up != "y" && up != "z") fail(src.at(*n), "'up' must be \"x\", \"y\" or \"z\"");
    r.mesh_up = up[0] - 'x';
  }
  if (auto* n = t.get("resolution")) {
    const int res = positive_int(*n, src, "resolution", 2, 8192);
    r.native = {res, res};
  }
  canon["up"] = r.mesh_up;
  if (auto* n = t.get("reverse_perspective")) {
    r.reverse_cop = number(*n, src, "reverse_perspective");
    if (!(r.reverse_cop > 1) || !(r.reverse_cop <= 1e4))
      fail(src.at(*n),
           "'reverse_perspective' is the depth of the centre of projection below the "
           "top, in box depths: it must be > 1 and at most 1e4 (beyond, the projection is "
           "orthographic to float precision: leave the key out), got " +
               format_number(r.reverse_cop));
    canon["reverse_perspective"] = r.reverse_cop;
  }
  canon["resolution"] = r.native.width;
  parse_layers(t, src, r, canon);
  if (r.layers > 0 && r.reverse_cop > 1)
    fail(src.at(node), "'layers' and 'reverse_perspective' cannot be combined yet");
  if (auto* n = t.get("open_surface_gap")) {
    // Open surfaces as two layers this far apart in depth (relief/layer_bake.h).
    if (r.layers == 0) fail(src.at(*n), "'open_surface_gap' applies to a mesh baked into 'layers'");
    const double gap = number(*n, src, "open_surface_gap");
    if (!(gap >= 0) || !(gap <= 0.5))
      fail(src.at(*n),
           "'open_surface_gap' is a depth in [0, 0.5] (0: two coincident layers), got " +
               format_number(gap));
    r.open_surface_gap = gap;
    canon["open_surface_gap"] = gap;
  }
  if (auto* n = t.get("three_views")) {
    // Policarpo & Oliveira 2006, Section 4: a bake along each axis, the nearest one drawn.
    r.three_views = boolean_of(*n, src, "three_views");
    if (r.three_views && r.layers == 0)
      fail(src.at(*n), "'three_views' bakes a relief impostor along each axis: it needs 'layers'");
    if (r.three_views) canon["three_views"] = true;  // absent when off: older scenes hash alike
  }
  if (auto* n = t.get("faces")) {
    // An object from several heightfields (Baboud & Decoret, Section 4.2).
    r.faces = positive_int(*n, src, "faces", 1, 6);
    if (r.faces != 1 && r.faces != 2 && r.faces != 3 && r.faces != 6)
      fail(src.at(*n),
           "'faces' must be 1 (top), 2 (top, bottom), 3 (top, +u, +v) or 6 (the "
           "whole cube), got " +
               std::to_string(r.faces));
    if (r.layers > 0) fail(src.at(*n), "'faces' and 'layers' cannot be combined");
    canon["faces"] = r.faces;
  }
}

// relief = { procedural = "kind", resolution, options, layers } (a heightfield or a pattern).
void parse_procedural_relief(const toml::table& t, const Src& src, ReliefSourceDesc& r,
                             nlohmann::json& canon) {
  r.procedural = string_of(*t.get("procedural"), src, "procedural");
  const bool pattern = is_pattern_mesh(r.procedural);
  bool known = pattern;
  for (const auto& k : procedural_kinds()) known |= k.name == r.procedural;
  if (!known) {
    std::string names;
    for (const auto& k : procedural_kinds()) names += (names.empty() ? "" : ", ") + k.name;
    std::string patterns;
    for (const auto& k : pattern_mesh_kinds()) patterns += (patterns.empty() ? "" : ", ") + k;
    fail(src.at(*t.get("procedural")), "unknown procedural relief '" + r.procedural +
                                           "' (known: " + names +
                                           "; non-height-field patterns: " + patterns + ")");
  }
  if (auto* n = t.get("resolution")) {
    const int res = positive_int(*n, src, "resolution", 2, 8192);
    r.native = {res, res};
  }
  if (auto* o = t.get("options")) {
    const toml::table* ot = o->as_table();
    if (!ot) fail(src.at(*o), "'options' must be a table");
    for (auto&& [k, v] : *ot)
      r.options[std::string(k.str())] = number(v, src, std::string(k.str()));
    // Validate option names and values now (the builders check them the same way).
    if (pattern)
      make_pattern_mesh(r.procedural, r.options, src.at(*o));
    else
      make_procedural(r.procedural, 4, r.options, 1.0, src.at(*o));
  }
  canon["procedural"] = r.procedural;
  canon["options"] = r.options;
  canon["resolution"] = r.native.width;
  parse_layers(t, src, r, canon);
  if (pattern && r.layers == 0) r.layers = 4;  // the paper's RGBA: four layers
  if (!pattern && r.layers > 0)
    fail(src.at(*t.get("layers")),
         "'layers' applies to meshes and the non-height-field "
         "patterns (weave, helix), not to heightfield '" +
             r.procedural + "'");
  if (pattern) canon["layers"] = r.layers;
}

// relief = { normal, depth, color, convention, flip_green, normalize } (image files).
void parse_image_relief(const toml::table& t, const toml::node& node, const Src& src,
                        const std::string& base_dir, ReliefSourceDesc& r, nlohmann::json& canon) {
  if (t.contains("layers"))
    fail(src.at(*t.get("layers")), "'layers' applies to meshes and non-height-field patterns");
  if (t.contains("resolution") || t.contains("options"))
    fail(src.at(node), "'resolution' and 'options' apply to procedural reliefs only");
  if (auto* n = t.get("normal"))
    r.normal_path = resolve_path(string_of(*n, src, "normal"), base_dir, src, *n);
  if (auto* n = t.get("depth"))
    r.depth_path = resolve_path(string_of(*n, src, "depth"), base_dir, src, *n);
  if (auto* n = t.get("color"))
    r.color_path = resolve_path(string_of(*n, src, "color"), base_dir, src, *n);
  if (auto* n = t.get("convention")) {
    std::string c = string_of(*n, src, "convention");
    if (c != "height" && c != "depth")
      fail(src.at(*n),
           "'convention' must be \"height\" (1 = top) or \"depth\" (0 = top), got \"" + c + "\"");
    r.height_convention = c == "height";
  }
  if (auto* n = t.get("flip_green")) r.flip_green = number_or_flag(*n, src, "flip_green") != 0;
  if (auto* n = t.get("normalize")) r.normalize = number_or_flag(*n, src, "normalize") != 0;
  if (auto* n = t.get("nodata")) {
    r.nodata = number(*n, src, "nodata");
    if (!std::isfinite(r.nodata))
      fail(src.at(*n),
           "'nodata' must be a finite number (the file's value for texels "
           "without data, e.g. -9999)");
    canon["nodata"] = r.nodata;  // only when given: keys of maps without it stay as they were
  }
  // The native size (any aspect) and the files' hashes come from read_scene_files().
  canon["convention"] = r.height_convention ? "height" : "depth";
  canon["flip_green"] = r.flip_green;
  canon["normalize"] = r.normalize;
}

}  // namespace

ReliefSourceDesc parse_relief(const toml::node& node, const Src& src, const std::string& base_dir,
                              nlohmann::json& canon) {
  const toml::table* t = node.as_table();
  if (!t) fail(src.at(node), "'relief' must be a table, e.g. { procedural = \"bricks\" }");
  ReliefSourceDesc r;
  if (t->contains("cells")) {
    for (const char* k : {"procedural", "normal", "depth", "mesh"})
      if (t->contains(k))
        fail(src.at(node), std::string("relief needs exactly one of 'procedural', image files, "
                                       "'mesh' or 'cells'; this one also has '") +
                               k + "'");
    parse_cells_relief(*t, src, base_dir, r, canon);
    return r;
  }
  check_keys(*t,
             {"procedural", "resolution", "options", "normal", "depth", "color", "convention",
              "flip_green", "normalize", "nodata", "mesh", "up", "reverse_perspective", "layers",
              "faces", "open_surface_gap", "three_views"},
             src, "relief");
  const bool procedural = t->contains("procedural");
  const bool images = t->contains("normal") || t->contains("depth");
  const bool mesh = t->contains("mesh");
  if (int(procedural) + int(images) + int(mesh) != 1)
    fail(src.at(node),
         "relief needs exactly one of 'procedural', image files ('normal' and/or "
         "'depth') or 'mesh'");
  if (mesh) {
    parse_mesh_relief(*t, node, src, base_dir, r, canon);
    return r;
  }
  for (const char* k : {"up", "reverse_perspective", "faces", "three_views"})
    if (t->contains(k))
      fail(src.at(node),
           "'up', 'reverse_perspective', 'faces' and 'three_views' apply to mesh reliefs only");
  // A procedural relief makes its own colour and depths: image keys beside it were silently
  // ignored, a missing colour file included.
  for (const char* k : {"color", "convention", "flip_green", "normalize", "nodata"})
    if (procedural && t->contains(k))
      fail(src.at(*t->get(k)), std::string("'") + k +
                                   "' applies to reliefs from image files; a procedural relief "
                                   "makes its own colour and depths");
  if (procedural)
    parse_procedural_relief(*t, src, r, canon);
  else
    parse_image_relief(*t, node, src, base_dir, r, canon);
  return r;
}

}  // namespace rl
