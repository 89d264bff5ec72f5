#include "technique/draws.h"

namespace rl {
namespace {

struct Words {
  const char* name;     // in a list of what a technique reads or draws on
  const char* refusal;  // why a technique that does not take it cannot draw a scene that is it
};

Words words(Representation r) {
  switch (r) {
    case Representation::Heightfield:
      return {"heightfield", "the scene is a single heightfield, which it does not read"};
    case Representation::Layers:
      return {"layers", "it reads a single heightfield (no multilayer map)"};
    case Representation::Impostor:
      return {"impostor",
              "the scene is a relief impostor (a mesh baked into layers, seen from both sides), "
              "which it does not search"};
    case Representation::MetaRuntime:
      return {"meta-relief per fetch",
              "it cannot combine the meta-relief layers at run time (its search needs one map); "
              "set combine = \"baked\" in the scene's meta_relief"};
    case Representation::HeightfieldObject:
      return {"heightfield object",
              "the scene is an object from several heightfields (relief = { mesh = ..., faces = "
              "N }), which only techniques that read every face's map draw"};
    case Representation::CellComplex:
      return {"cell complex",
              "the scene is a cell complex (relief = { cells = ... }), which only the "
              "cell-complex techniques read"};
  }
  return {"", ""};
}

Words words(BaseShape b) {
  return b == BaseShape::Planar
             ? Words{"planar base", "the base is planar, where it does not draw"}
             : Words{"curved base", "it draws on the planar base only (no curved base)"};
}

Words words(Proxy p) {
  return p == Proxy::Base ? Words{"base surface",
                                  "it draws the relief as the closed solid in its box; set "
                                  "proxy = \"box\""}
                          : Words{"box proxy", "proxy = \"box\" (it only shades the base surface)"};
}

Words words(Projection p) {
  return p == Projection::Plain
             ? Words{"plain projection", "it draws reverse-perspective reliefs only"}
             : Words{"reverse perspective",
                     "it does not draw a reverse-perspective relief (the projection's centre)"};
}

// The first value of E's `count` values among `choices`, in words, joined by ", ".
template <typename E>
std::string names(const Choices<E>& choices, int count) {
  std::string out;
  for (int i = 0; i < count; ++i)
    if (choices.has(E(i))) out += (out.empty() ? "" : ", ") + std::string(words(E(i)).name);
  return out;
}

}  // namespace

SceneInputs scene_inputs(const SceneDesc& s) {
  SceneInputs in;
  in.relief = s.cell_complex()         ? Representation::CellComplex
              : s.heightfield_object() ? Representation::HeightfieldObject
              : s.impostor()           ? Representation::Impostor
              : s.meta.runtime()       ? Representation::MetaRuntime
              : s.relief.layers > 0    ? Representation::Layers
                                       : Representation::Heightfield;
  in.base = s.base.curved() ? BaseShape::Curved : BaseShape::Planar;
  in.proxy = s.proxy;
  in.projection = s.projection.active() ? Projection::ReversePerspective : Projection::Plain;
  return in;
}

std::string cannot_draw(const Draws& draws, const SceneDesc& scene) {
  const SceneInputs in = scene_inputs(scene);
  if (!draws.reads.has(in.relief)) {
    // A technique of one representation says so rather than what the scene is.
    if (draws.reads.only(Representation::CellComplex))
      return "it renders cell-complex reliefs (relief = { cells = ... }) only";
    if (draws.reads.only(Representation::HeightfieldObject))
      return "it renders objects from several heightfields (relief = { mesh = ..., faces = N }) "
             "only";
    return words(in.relief).refusal;
  }
  if (!draws.bases.has(in.base)) return words(in.base).refusal;
  if (!draws.projections.has(in.projection)) return words(in.projection).refusal;
  if (!draws.proxies.has(in.proxy)) return words(in.proxy).refusal;
  return "";
}

std::string reads_in_words(const Draws& draws) {
  return names(draws.reads, 6);
}

std::string draws_on_in_words(const Draws& draws) {
  std::string bases = names(draws.bases, 2);
  if (draws.bases.has(BaseShape::Planar) && draws.bases.has(BaseShape::Curved))
    bases = "planar or curved base";
  std::string out = bases;
  if (draws.proxies.has(Proxy::Box))
    out += draws.proxies.has(Proxy::Base) ? ", or the relief's box proxy" : ", box proxy only";
  if (!draws.projections.has(Projection::ReversePerspective)) out += " (no reverse perspective)";
  return out;
}

}  // namespace rl
