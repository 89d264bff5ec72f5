#include "core/effects.h"

#include <algorithm>
#include <cctype>

namespace rl {

const std::vector<Effect>& all_effects() {
  static const std::vector<Effect> effects = {Effect::SelfShadow, Effect::Silhouette,
                                              Effect::DepthCorrect, Effect::AmbientOcclusion,
                                              Effect::SceneShadows};
  return effects;
}

std::vector<Effect> EffectSet::list() const {
  std::vector<Effect> out;
  for (Effect e : all_effects())
    if (has(e)) out.push_back(e);
  return out;
}

std::string effect_name(Effect e) {
  switch (e) {
    case Effect::SelfShadow:
      return "self_shadow";
    case Effect::Silhouette:
      return "silhouette";
    case Effect::DepthCorrect:
      return "depth_correct";
    case Effect::AmbientOcclusion:
      return "ambient_occlusion";
    case Effect::SceneShadows:
      return "scene_shadows";
  }
  return "unknown";
}

std::string effect_define(Effect e) {
  std::string name = effect_name(e);
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return "RL_" + name;
}

std::optional<Effect> parse_effect(const std::string& name) {
  for (Effect e : all_effects())
    if (effect_name(e) == name) return e;
  return std::nullopt;
}

std::string join_effects(EffectSet set) {
  std::string out;
  for (Effect e : set.list()) out += (out.empty() ? "" : ", ") + effect_name(e);
  return out.empty() ? "none" : out;
}

}  // namespace rl
