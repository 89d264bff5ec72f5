#include "config/config_effects.h"

namespace rl {
namespace {

using MapMethod = AmbientOcclusionDesc::MapMethod;
constexpr std::pair<MapMethod, const char*> kMapMethods[] = {
    {MapMethod::LineSweep, "line_sweep"},
    {MapMethod::March, "march"},
    {MapMethod::FragmentShader, "fragment_shader"}};

const char* ao_map_method_name(MapMethod m) {
  for (const auto& [method, name] : kMapMethods)
    if (method == m) return name;
  return "line_sweep";
}

MapMethod ao_map_method_of(const toml::node& n, const Src& src) {
  const std::string name = string_of(n, src, "map_method");
  for (const auto& [method, known] : kMapMethods)
    if (name == known) return method;
  fail(src.at(n),
       "'map_method' must be \"line_sweep\" (the CPU's line sweep, the default), \"march\" (the "
       "paper's per-texel march on the CPU) or \"fragment_shader\" (that march on the GPU), got "
       "\"" +
           name + "\"");
}

}  // namespace

void parse_effect_options(const toml::table& t, const Src& src, const toml::node& scene_node,
                          SceneDesc& s, nlohmann::json& canon) {
  const bool wanted = s.effects.has(Effect::AmbientOcclusion);
  const toml::node* options = t.get("ambient_occlusion");
  if (options && !wanted)
    fail(src.at(*options), "scene '" + s.name +
                               "': 'ambient_occlusion' options are given but the scene does not "
                               "ask for the effect (add \"ambient_occlusion\" to 'effects')");
  if (!wanted) return;
  // Texture-space AO is a heightfield's: a map of horizons over one surface per texel.
  const std::string no = "scene '" + s.name + "': ambient_occlusion needs a heightfield relief ";
  if (s.relief.layers > 0) fail(src.at(scene_node), no + "(not a multilayer one)");
  if (!s.relief.mesh_path.empty()) fail(src.at(scene_node), no + "(not a baked mesh)");
  if (s.proxy == Proxy::Box)
    fail(src.at(scene_node), no + "drawn on its base (not proxy = \"box\")");
  if (options) {
    const toml::table* o = options->as_table();
    if (!o)
      fail(src.at(*options),
           "'ambient_occlusion' must be a table, e.g. { map_depth = 0.04, update = \"eq6\" }");
    check_keys(*o,
               {"directions", "filter", "map_depth", "map_method", "update", "samples",
                "stderr_target", "render"},
               src, "ambient_occlusion");
    if (auto* n = o->get("directions"))
      s.ao.directions = positive_int(*n, src, "directions", 8, 720);
    if (auto* n = o->get("filter")) s.ao.filter = boolean_of(*n, src, "filter");
    if (auto* n = o->get("map_depth")) s.ao.map_depth = number_in(*n, src, "map_depth", 1e-4, 10);
    if (auto* n = o->get("update")) {
      const std::string u = string_of(*n, src, "update");
      if (u != "eq6" && u != "none")
        fail(src.at(*n),
             "'update' must be \"eq6\" (Eq. 6 from the stored map) or \"none\" (the "
             "map as stored), got \"" +
                 u + "\"");
      s.ao.update =
          u == "eq6" ? AmbientOcclusionDesc::Update::Eq6 : AmbientOcclusionDesc::Update::None;
    }
    if (auto* n = o->get("samples")) s.ao.samples = positive_int(*n, src, "samples", 1, 65536);
    if (auto* n = o->get("stderr_target"))
      s.ao.stderr_target = number_in(*n, src, "stderr_target", 0, 0.5);
    if (auto* n = o->get("render")) s.ao.render = boolean_of(*n, src, "render");
    if (auto* n = o->get("map_method")) s.ao.map_method = ao_map_method_of(*n, src);
  }
  canon["ambient_occlusion"] = {
      {"directions", s.ao.directions},
      {"filter", s.ao.filter},
      {"map_depth", s.ao.map_depth},
      {"update", s.ao.update == AmbientOcclusionDesc::Update::Eq6 ? "eq6" : "none"},
      {"samples", s.ao.samples},
      {"stderr_target", s.ao.stderr_target}};
  // Only where set, so that every earlier AO scene keeps its key.
  if (!s.ao.render) canon["ambient_occlusion"]["render"] = false;
  if (s.ao.map_method != AmbientOcclusionDesc::MapMethod::LineSweep)
    canon["ambient_occlusion"]["map_method"] = ao_map_method_name(s.ao.map_method);
}

void parse_scene_shadows(const toml::table& t, const Src& src, const toml::node& scene_node,
                         SceneDesc& s, nlohmann::json& canon) {
  const bool wanted = s.effects.has(Effect::SceneShadows);
  const toml::node* options = t.get("shadow_map");
  if (options && !wanted)
    fail(src.at(*options), "scene '" + s.name +
                               "': 'shadow_map' options are given but the scene does not ask "
                               "for the effect (add \"scene_shadows\" to 'effects')");
  if (!wanted) return;
  // What the shadow map is built for: the relief drawn on its base, planar or curved.
  const std::string no = "scene '" + s.name + "': scene_shadows needs ";
  if (s.proxy == Proxy::Box || s.in_cube())
    fail(src.at(scene_node), no + "the relief drawn on its base (not in a box proxy)");
  if (s.impostor()) fail(src.at(scene_node), no + "a relief on its base (not an impostor)");
  if (s.relief.reverse_cop > 0)
    fail(src.at(scene_node), no + "the plain projection (not reverse_perspective)");
  if (options) {
    const toml::table* o = options->as_table();
    if (!o)
      fail(src.at(*options),
           "'shadow_map' must be a table, e.g. { size = 2048, depth = \"corrected\", bias = "
           "0.002, slope_bias = 1 }");
    check_keys(*o, {"size", "depth", "bias", "slope_bias"}, src, "shadow_map");
    if (auto* n = o->get("size")) s.shadow_map.size = positive_int(*n, src, "size", 16, 8192);
    if (auto* n = o->get("bias")) s.shadow_map.bias = number_in(*n, src, "bias", 0, 1);
    if (auto* n = o->get("slope_bias"))
      s.shadow_map.slope_bias = number_in(*n, src, "slope_bias", 0, 100);
    if (auto* n = o->get("depth")) {
      const std::string d = string_of(*n, src, "depth");
      if (d != "corrected" && d != "base")
        fail(src.at(*n),
             "'depth' must be \"corrected\" (the relief at its found hit's depth) or \"base\" "
             "(at its base's), got \"" +
                 d + "\"");
      s.shadow_map.corrected_depth = d == "corrected";
    }
  }
  try {
    (void)light_camera(s);
  } catch (const std::runtime_error& e) {
    fail(src.at(t.get("light") ? *t.get("light") : scene_node), e.what());
  }
  canon["shadow_map"] = {{"size", s.shadow_map.size},
                         {"depth", s.shadow_map.corrected_depth ? "corrected" : "base"},
                         {"bias", s.shadow_map.bias},
                         {"slope_bias", s.shadow_map.slope_bias}};
}

}  // namespace rl
