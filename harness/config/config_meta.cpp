#include "config/config_meta.h"

#include "config/config_relief.h"
#include "relief/relief_map.h"

namespace rl {
namespace {

// w_n and w_d of one layer: `weight` sets both; `weight_normal`, `weight_depth` each.
void parse_weights(const toml::table& t, const Src& src, double& normal, double& depth) {
  if (auto* n = t.get("weight")) normal = depth = number_in(*n, src, "weight", 0, 1e6);
  if (auto* n = t.get("weight_normal")) normal = number_in(*n, src, "weight_normal", 0, 1e6);
  if (auto* n = t.get("weight_depth")) depth = number_in(*n, src, "weight_depth", 0, 1e6);
}

// A meta-relief layer is one heightfield per texel: a procedural map or image files.
void require_heightfield(const ReliefSourceDesc& r, const Src& src, const toml::node& node,
                         const std::string& what) {
  if (!r.mesh_path.empty() || r.pattern_mesh() || r.layers > 0)
    fail(src.at(node), what +
                           " must be a heightfield (a procedural map or image files), not a "
                           "mesh or a multilayer pattern");
}

// Layer i of [[scene.meta_relief.layers]]: its relief (a heightfield), tiling and weights, and
// their canonical description in `lc`.
MetaLayerDesc parse_meta_layer(const toml::node& ln, size_t i, const Src& src,
                               const std::string& base_dir, const std::string& scene,
                               nlohmann::json& lc) {
  const toml::table* lt = ln.as_table();
  if (!lt) fail(src.at(ln), "each meta_relief layer must be a table with a 'relief'");
  check_keys(*lt, {"relief", "tiling", "weight", "weight_normal", "weight_depth"}, src,
             "meta_relief layer");
  MetaLayerDesc layer;
  if (!lt->contains("relief")) fail(src.at(ln), "a meta_relief layer needs a 'relief'");
  layer.relief = parse_relief(*lt->get("relief"), src, base_dir, lc["relief"]);
  require_heightfield(layer.relief, src, *lt->get("relief"),
                      scene + "meta_relief layer " + std::to_string(i + 1));
  if (auto* n = lt->get("tiling")) {
    layer.tiling = number(*n, src, "tiling");
    if (!(layer.tiling > 0) || layer.tiling > 1e3)
      fail(src.at(*n),
           "'tiling' is how often the layer repeats per base tile: it must be "
           "above 0 and at most 1000, got " +
               format_number(layer.tiling));
  }
  parse_weights(*lt, src, layer.weight_normal, layer.weight_depth);
  lc["tiling"] = layer.tiling;
  lc["weights"] = {layer.weight_normal, layer.weight_depth};
  return layer;
}

// How the layers are combined: per fetch or baked, the bake's resolutions, and their AO maps.
void parse_combination(const toml::table& m, const Src& src, const EffectSet& effects,
                       const std::string& scene, MetaReliefDesc& meta) {
  if (auto* n = m.get("combine")) {
    const std::string how = string_of(*n, src, "combine");
    if (how != "runtime" && how != "baked")
      fail(src.at(*n),
           "'combine' must be \"runtime\" (every layer sampled per fetch) or "
           "\"baked\" (one map of the combination), got \"" +
               how + "\"");
    meta.combine =
        how == "baked" ? MetaReliefDesc::Combine::Baked : MetaReliefDesc::Combine::Runtime;
  }
  if (auto* n = m.get("bake_resolution"))
    meta.bake_resolution = positive_int(*n, src, "bake_resolution", 2, 8192);
  if (auto* n = m.get("color_resolution"))
    meta.color_resolution = positive_int(*n, src, "color_resolution", 2, 8192);
  if (auto* n = m.get("ao_combine")) {
    if (!effects.has(Effect::AmbientOcclusion))
      fail(src.at(*n), scene + "'ao_combine' needs the ambient_occlusion effect");
    const std::string how = string_of(*n, src, "ao_combine");
    if (how != "product" && how != "min" && how != "bake")
      fail(src.at(*n),
           "'ao_combine' must be \"product\" or \"min\" (of the layers' AO maps, "
           "Section IV-A) or \"bake\" (the AO map of the bake), got \"" +
               how + "\"");
    meta.ao_combine = how == "min"    ? MetaReliefDesc::AoCombine::Min
                      : how == "bake" ? MetaReliefDesc::AoCombine::Bake
                                      : MetaReliefDesc::AoCombine::Product;
  }
}

}  // namespace

void parse_meta_relief(const toml::table& t, const Src& src, const std::string& base_dir,
                       const toml::node& scene_node, SceneDesc& s, nlohmann::json& canon) {
  const toml::node* node = t.get("meta_relief");
  if (!node) return;
  const toml::table* m = node->as_table();
  if (!m)
    fail(src.at(*node),
         "'meta_relief' must be a table with 'layers', e.g. [scene.meta_relief] and "
         "[[scene.meta_relief.layers]] sections");
  check_keys(*m,
             {"layers", "weight", "weight_normal", "weight_depth", "combine", "bake_resolution",
              "color_resolution", "ao_combine"},
             src, "meta_relief");
  const std::string scene = "scene '" + s.name + "': ";
  require_heightfield(s.relief, src, scene_node, scene + "the relief under a meta-relief");
  if (s.proxy == Proxy::Box) fail(src.at(scene_node), scene + "a meta-relief is drawn on its base");
  if (s.truth != TruthLevel::Sampled)
    fail(src.at(scene_node), scene +
                                 "a meta-relief's truth is its layers' combination "
                                 "(truth = \"sampled\")");
  MetaReliefDesc& meta = s.meta;
  nlohmann::json& c = canon["meta_relief"];
  parse_weights(*m, src, meta.weight_normal, meta.weight_depth);
  const toml::node* layers = m->get("layers");
  const toml::array* list = layers ? layers->as_array() : nullptr;
  if (!list || list->empty())
    fail(
        src.at(layers ? *layers : *node),
        "'meta_relief' needs 'layers': a list of { relief = { ... }, tiling = ..., weight = ... }");
  if (list->size() + 1 > size_t(kMaxMetaLayers))
    fail(src.at(*layers), "a meta-relief has at most " + std::to_string(kMaxMetaLayers) +
                              " layers with the scene's relief; got " +
                              std::to_string(list->size() + 1));
  double sum_normal = meta.weight_normal, sum_depth = meta.weight_depth;
  for (size_t i = 0; i < list->size(); ++i) {
    meta.layers.push_back(parse_meta_layer(*list->get(i), i, src, base_dir, scene, c["layers"][i]));
    sum_normal += meta.layers.back().weight_normal;
    sum_depth += meta.layers.back().weight_depth;
  }
  if (!(sum_normal > 0))
    fail(src.at(*node), scene +
                            "the meta-relief's normal weights (weight_normal) sum to zero; "
                            "Eq. 1 divides by their sum");
  if (!(sum_depth > 0))
    fail(src.at(*node), scene +
                            "the meta-relief's depth weights (weight_depth) sum to zero; "
                            "Eq. 2 divides by their sum");
  parse_combination(*m, src, s.effects, scene, meta);
  c["weights"] = {meta.weight_normal, meta.weight_depth};
  c["combine"] = meta.combine == MetaReliefDesc::Combine::Baked ? "baked" : "runtime";
  c["bake_resolution"] = meta.bake_resolution;
  if (meta.color_resolution > 0) c["color_resolution"] = meta.color_resolution;
  if (s.effects.has(Effect::AmbientOcclusion))
    c["ao_combine"] = meta.ao_combine == MetaReliefDesc::AoCombine::Min    ? "min"
                      : meta.ao_combine == MetaReliefDesc::AoCombine::Bake ? "bake"
                                                                           : "product";
}

}  // namespace rl
