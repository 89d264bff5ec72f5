#pragma once
// Effects a scene can ask for. A technique declares which it supports; a shader is compiled
// with exactly the requested ones (as RL_<NAME> defines) and the truth traces only them.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rl {

enum class Effect : uint32_t {
  SelfShadow = 1u << 0,    // shadow ray through the relief (chapter 5, Listing 5.3)
  Silhouette = 1u << 1,    // discard rays leaving the relief volume (curved bases)
  DepthCorrect = 1u << 2,  // write the depth of the found hit
  // Texture-space ambient occlusion (Limberger et al., Section IV): ambient light scaled by
  // the AO map at the hit; the truth samples the hemisphere with Embree.
  AmbientOcclusion = 1u << 3,
  // Shadows among all the scene's surfaces -- the relief and the plain objects cast on each
  // other and on themselves -- from a shadow map the light renders, the relief drawn into it at
  // its found hit's depth (Policarpo & Oliveira 2006, Section 7; chapter 5, "Depth Correct");
  // the truth traces a shadow ray from every visible point.
  SceneShadows = 1u << 4,
  // Only effects something implements are declared, so `relieflab list` never advertises one
  // nothing does.
};

class EffectSet {
 public:
  EffectSet() = default;
  EffectSet(std::initializer_list<Effect> effects) {
    for (Effect e : effects) add(e);
  }
  void add(Effect e) { bits_ |= static_cast<uint32_t>(e); }
  bool has(Effect e) const { return (bits_ & static_cast<uint32_t>(e)) != 0; }
  bool empty() const { return bits_ == 0; }
  bool contains_all(EffectSet other) const { return (other.bits_ & ~bits_) == 0; }
  void remove(Effect e) { bits_ &= ~static_cast<uint32_t>(e); }
  // Effects in `other` that this set lacks.
  EffectSet missing_from(EffectSet other) const {
    EffectSet r;
    r.bits_ = other.bits_ & ~bits_;
    return r;
  }
  std::vector<Effect> list() const;
  bool operator==(const EffectSet& o) const { return bits_ == o.bits_; }

 private:
  uint32_t bits_ = 0;
};

const std::vector<Effect>& all_effects();
std::string effect_name(Effect e);    // "self_shadow"
std::string effect_define(Effect e);  // "RL_SELF_SHADOW"
std::optional<Effect> parse_effect(const std::string& name);
std::string join_effects(EffectSet set);  // "self_shadow, silhouette" or "none"

}  // namespace rl
