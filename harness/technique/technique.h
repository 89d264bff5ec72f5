#pragma once
// The technique plugin interface. A technique is a class registered by name with
// RL_REGISTER_TECHNIQUE (like Mitsuba's plugin macros). Its static describe() gives the
// citation, the effects it supports and its parameters (designated initializers, checked at
// registration), so a config is checked before any work; an optional static
// validate(params, where) rejects parameter combinations (e.g. min_samples > max_samples)
// for every setting of a sweep before its first cell. An instance is made per parameter
// setting, prepared once per relief asset (timed as precompute), then rendered per view.
//
// One parameter namespace: a parameter name is one rows.csv column and one table field
// across all techniques, so two techniques may share a name only for the same quantity; the
// registry refuses a shared name whose kind differs.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/columns.h"
#include "core/effects.h"
#include "core/params.h"
#include "gl/render_target.h"
#include "gpu/gpu_scene.h"
#include "relief/relief_map.h"
#include "scene/scene.h"
#include "technique/contract.h"
#include "technique/draws.h"
#include "technique/object_pass.h"
#include "technique/shadow_map_pass.h"

namespace rl {

struct TechniqueInfo {
  std::string name;      // registry key, e.g. "relief"
  std::string title;     // e.g. "Relief mapping (linear + binary search)"
  std::string citation;  // paper and section
  EffectSet effects;     // effects it can simulate when a scene asks for them
  std::vector<ParamSpec> params;
  // What it reads and draws on (technique/draws.h): a heightfield or layers on any base, on
  // the base surface, unless it declares otherwise.
  Draws draws{};
  // What it promises (technique/contract.h), held to by the contract suite.
  TechniqueContract contract;
  // The columns its frame_columns() writes (core/columns.h), declared when it registers.
  std::vector<ColumnSpec> columns{};
  // Why one of its settings cannot draw `scene` ("" when it can), beyond what `draws` says
  // for every setting (relief's mip-mapped reads on a meta-relief combined per fetch, whose
  // layers have no mip levels). Asked for every setting and scene when the config is read.
  std::function<std::string(const ParamValues& setting, const SceneDesc& scene)>
      setting_cannot_render{};
};

// Why a technique cannot render `scene` ("" when it can): effects it does not simulate, or a
// scene input outside what it declares it draws (technique/draws.h). Config checks and the
// tests that iterate the registry ask the same question.
std::string cannot_render(const TechniqueInfo& info, const SceneDesc& scene);

// Throws std::logic_error naming the technique when its metadata is inconsistent: an empty or
// non-identifier name, a duplicate parameter, min > max, a default outside its range, a
// non-integer int/bool default, a bool range other than [0, 1].
void check_technique_info(const TechniqueInfo& info);

// What render() draws with: the scene, its GPU resources and the view.
struct FrameInput {
  const SceneDesc& scene;
  const ReliefMap& map;
  const GpuRelief& relief;
  const GpuBase& base;
  const Camera& camera;
  EffectSet effects;                    // exactly the scene's requested effects
  const ObjectPass* objects = nullptr;  // the scene's plain objects, if any
  // scene_shadows: the light's shadow map, drawn before the frame; the relief and the objects
  // receive its shadows.
  const ShadowMapPass* shadow_map = nullptr;
  // Drawing the relief into the shadow map (`camera` is the light's): only the depth counts.
  bool shadow_caster = false;
};

// A tangent-space ray for ray-probe mode: (u, v, depth)(t) = origin + t * direction, with
// direction.z = 1 (t counts depth units).
struct ProbeRay {
  glm::vec3 origin;
  glm::vec3 direction;
  glm::vec2 quadric{0.0f};  // base curvature (A, B) in texture units, for ray-bending techniques
};

struct ProbeHit {
  float t = 0;
  glm::vec2 uv{0};
  float depth = 0;
  int layer = 0;
  bool hit = false;
  int fetches = 0;
};

class Technique {
 public:
  explicit Technique(ParamValues params) : params_(std::move(params)) {}
  virtual ~Technique() = default;
  virtual const TechniqueInfo& info() const = 0;

  // Offline work on the asset (safety radii, cone maps, curvature...). Timed by the harness.
  virtual void prepare(const ReliefMap& map) { (void)map; }
  // The same, for work that depends on the scene's proportions too (a map of world-space
  // directions); the harness calls this one. By default, prepare(map).
  virtual void prepare_scene(const SceneDesc& scene, const ReliefMap& map) {
    (void)scene;
    prepare(map);
  }
  // Draws the base (or the technique's own proxy geometry) into the bound render target.
  // A ColorOnly target is the timing variant: no G-buffer outputs are compiled in.
  virtual void render(const FrameInput& frame, RenderTarget::Kind target) = 0;
  // Runs the technique's intersection routine on a batch of tangent-space rays.
  // `depth_aspect`: world relief depth / world length of one unit of u and of v.
  virtual std::vector<ProbeHit> probe(const ReliefMap& map, const GpuRelief& relief,
                                      const std::vector<ProbeRay>& rays,
                                      glm::dvec2 depth_aspect) = 0;
  // Bytes of the technique's own textures and buffers, beyond the shared relief + colour maps.
  virtual size_t memory_bytes() const { return 0; }
  // True when prepare() loaded its precomputation from a cache instead of computing it.
  virtual bool prepared_from_cache() const { return false; }
  // Columns the technique measured during its last G-buffer render, beyond the harness's (a
  // multi-pass technique's passes and fragments shaded per pixel); named in rows.csv as given,
  // each declared in describe().columns (the runner refuses one that is not).
  virtual std::vector<std::pair<std::string, double>> frame_columns() const { return {}; }

  const ParamValues& params() const { return params_; }
  // A parameter read as its declared kind (core/params.h typed_param): param<int>("slices"),
  // param<bool>("mipmap"), param<double>("error_allowed"). A technique reads each once, into a
  // typed member when it is created (a default member initialiser may call it: info() is the
  // technique's own by then); std::logic_error names one it does not declare or reads as another
  // kind.
  template <typename T>
  T param(const std::string& name) const {
    return typed_param<T>(info().params, params_, name, "technique '" + info().name + "'");
  }
  // The GLSL defines its declared parameters set at this setting (ParamSpec::define), for the
  // techniques that build their own programs.
  std::map<std::string, std::string> declared_defines() const {
    return param_defines(info().params, params_);
  }

 protected:
  ParamValues params_;
};

// Implements info() from the technique's static describe(), which the registrar also reads:
//   class ReliefMapping final : public Described<ReliefMapping, ShaderTechnique> { ... };
template <typename Self, typename Base>
class Described : public Base {
 public:
  using Base::Base;
  const TechniqueInfo& info() const override {
    static const TechniqueInfo i = Self::describe();
    return i;
  }
};

// One frame of a cell into the bound target: the shadow map where the scene has one
// (render_shadow_map), then the scene itself (render_scene).
void render_frame(Technique& technique, const FrameInput& frame, RenderTarget::Kind target);
// The light's shadow map of scene_shadows, if the frame has one; nothing otherwise.
void render_shadow_map(Technique& technique, const FrameInput& frame);
// The scene's objects, then the technique's relief (which, with depth_correct, resolves
// visibility against them per pixel), each receiving the shadow map's shadows if it has one.
void render_scene(Technique& technique, const FrameInput& frame, RenderTarget::Kind target);

struct TechniqueEntry {
  TechniqueInfo info;
  std::function<std::unique_ptr<Technique>(const ParamValues&)> create;
  // Cross-parameter check of a full setting (defaults filled in); throws ConfigError naming
  // `where`. Empty: every in-range combination is valid.
  std::function<void(const ParamValues&, const std::string& where)> validate;
  std::string source;  // the file that registered it, for messages
  std::string plugin;  // the shared object it came from (technique/plugins.h); "" if built in
};

class TechniqueRegistry {
 public:
  static TechniqueRegistry& instance();
  // Registers a technique; throws std::logic_error when its metadata is inconsistent, its name
  // is taken (naming both registering files) or a parameter name it shares with another
  // technique has a different kind.
  void add(TechniqueEntry entry);
  // Unregisters (tests that register throwaway techniques clean up after themselves).
  void remove(const std::string& name);
  // Records the shared object `name` was loaded from (technique/plugins.h).
  void set_plugin(const std::string& name, const std::string& path);
  const TechniqueEntry* find(const std::string& name) const;
  std::vector<std::string> names() const;
  // `name`'s defaults overridden by `params`, range-checked and validated; throws ConfigError
  // naming `where` on unknown names, bad values or a rejected combination.
  ParamValues resolve(const std::string& name, const ParamValues& params,
                      const std::string& where) const;
  // Creates `name` with resolve()'s parameters.
  std::unique_ptr<Technique> create(const std::string& name, const ParamValues& params,
                                    const std::string& where) const;

 private:
  void refuse_parameters_named_like_columns(const TechniqueEntry& entry) const;
  std::map<std::string, TechniqueEntry> entries_;
};

// add(), and on a refusal a message on stderr and exit(3): registration runs before main(),
// where nothing could catch it. While a plugin loads (technique/plugins.h), a refusal is
// appended to the sink set here instead, and the loader reports it.
void register_or_exit(TechniqueEntry entry);
void refuse_registration(const std::string& why);
void set_registration_error_sink(std::string* sink);

template <typename T>
struct TechniqueRegistrar {
  TechniqueRegistrar(const char* source, const char* class_name) {
    TechniqueEntry e;
    // An exception may not leave a static initialiser (it would end the process unnamed).
    try {
      e.info = T::describe();
    } catch (const std::exception& x) {
      refuse_registration(std::string(class_name) + "::describe() (" + source +
                          ") threw: " + x.what());
      return;
    } catch (...) {
      refuse_registration(std::string(class_name) + "::describe() (" + source +
                          ") threw something that is not a std::exception");
      return;
    }
    e.create = [](const ParamValues& p) { return std::make_unique<T>(p); };
    if constexpr (requires(const ParamValues& p, const std::string& w) { T::validate(p, w); })
      e.validate = [](const ParamValues& p, const std::string& w) { T::validate(p, w); };
    e.source = source;
    register_or_exit(std::move(e));
  }
};

#define RL_REGISTER_TECHNIQUE(Class) \
  static const ::rl::TechniqueRegistrar<Class> rl_technique_registrar_##Class(__FILE__, #Class)

}  // namespace rl
