#pragma once
// What a technique reads and draws on, declared in its describe() the way a render pass
// declares its inputs (Falcor's reflect()): one set of choices per axis -- the representation
// of the relief, the base's shape, the proxy the relief is drawn on, the projection. A scene
// states one value per axis (scene_inputs); a technique draws it when every value is among its
// choices, and a refusal names the first axis that is not, in that axis's own words. A new
// representation is one enum value (with its words in draws.cpp) and the techniques that read
// it.
#include <cstdint>
#include <initializer_list>
#include <string>

#include "scene/scene.h"

namespace rl {

enum class Representation : uint8_t {
  Heightfield,        // one depth map (a meta-relief's bake included)
  Layers,             // a multilayer map (relief.layers > 0), seen from above
  Impostor,           // a multilayer map of a baked mesh, seen from both sides
  MetaRuntime,        // a meta-relief whose layers are combined per fetch
  HeightfieldObject,  // an object from several heightfields, one map per cube face
  CellComplex,        // a mesh encoded as a cubic cell complex
};
enum class BaseShape : uint8_t { Planar, Curved };
enum class Projection : uint8_t { Plain, ReversePerspective };

// A set of an axis's values.
template <typename E>
class Choices {
 public:
  constexpr Choices(std::initializer_list<E> values) {
    for (E v : values) bits_ |= bit(v);
  }
  constexpr bool has(E v) const { return (bits_ & bit(v)) != 0; }
  // Exactly this one value.
  constexpr bool only(E v) const { return bits_ == bit(v); }

 private:
  static constexpr uint32_t bit(E v) { return uint32_t(1) << unsigned(v); }
  uint32_t bits_ = 0;
};

struct Draws {
  // By default: a heightfield or a multilayer map seen from above, on any base, on the base
  // surface (no box proxy), in either projection.
  Choices<Representation> reads{Representation::Heightfield, Representation::Layers};
  Choices<BaseShape> bases{BaseShape::Planar, BaseShape::Curved};
  Choices<Proxy> proxies{Proxy::Base};
  Choices<Projection> projections{Projection::Plain, Projection::ReversePerspective};
};

// What a scene gives a technique, one value per axis.
struct SceneInputs {
  Representation relief = Representation::Heightfield;
  BaseShape base = BaseShape::Planar;
  Proxy proxy = Proxy::Base;
  Projection projection = Projection::Plain;
};
SceneInputs scene_inputs(const SceneDesc& scene);

// Why a technique declaring `draws` cannot draw `scene` ("" when it can).
std::string cannot_draw(const Draws& draws, const SceneDesc& scene);

// Its choices in words, for the generated docs and `relieflab list`: the representations read
// ("heightfield, layers, meta-relief per fetch") and what it draws on ("planar or curved base,
// box proxy").
std::string reads_in_words(const Draws& draws);
std::string draws_on_in_words(const Draws& draws);

}  // namespace rl
