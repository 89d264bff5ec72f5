#include "technique/technique.h"

#include "core/error.h"

namespace rl {

void render_frame(Technique& technique, const FrameInput& frame, RenderTarget::Kind target) {
  if (frame.objects) frame.objects->draw(frame.scene, frame.camera, target);
  technique.render(frame, target);
}

TechniqueRegistry& TechniqueRegistry::instance() {
  static TechniqueRegistry registry;
  return registry;
}

void TechniqueRegistry::add(TechniqueEntry entry) {
  const std::string name = entry.info.name;
  entries_[name] = std::move(entry);
}

const TechniqueEntry* TechniqueRegistry::find(const std::string& name) const {
  auto it = entries_.find(name);
  return it == entries_.end() ? nullptr : &it->second;
}

std::vector<std::string> TechniqueRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& [name, e] : entries_) out.push_back(name);
  return out;
}

std::unique_ptr<Technique> TechniqueRegistry::create(const std::string& name,
                                                     const ParamValues& params,
                                                     const std::string& where) const {
  const TechniqueEntry* e = find(name);
  if (!e) {
    std::string known;
    for (const auto& n : names()) known += (known.empty() ? "" : ", ") + n;
    throw ConfigError(where + ": unknown technique '" + name + "' (known: " + known + ")");
  }
  return e->create(resolve_params(e->info.params, params, where));
}

}  // namespace rl
