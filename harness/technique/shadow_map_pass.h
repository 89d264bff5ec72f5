#pragma once
// The shadow map of scene_shadows (core/effects.h): the light's view of the scene's depth, drawn
// before the frame -- the plain objects, then the relief by the technique itself as a shadow
// caster, each fragment at the depth of the hit its search found (chapter 5, "Depth Correct";
// Policarpo & Oliveira 2006, Section 7), or at its base's where the scene says so -- and read
// by every surface the frame shades (harness/glsl/shadow_map.glsl).
#include <epoxy/gl.h>

#include "scene/scene.h"

namespace rl {

class Technique;
struct FrameInput;

class ShadowMapPass {
 public:
  // Throws std::runtime_error naming the scene where its light cannot see it whole
  // (scene/scene.h, light_camera).
  explicit ShadowMapPass(const SceneDesc& scene);
  ~ShadowMapPass();
  ShadowMapPass(const ShadowMapPass&) = delete;
  ShadowMapPass& operator=(const ShadowMapPass&) = delete;

  const Camera& camera() const { return camera_; }
  int size() const { return camera_.width; }
  // Draws `frame`'s objects and relief (by `technique`) from the light into the map; the
  // framebuffer and viewport bound before are bound again after.
  void render(Technique& technique, const FrameInput& frame) const;
  // Binds the map and sets its uniforms for `program`, a pass that receives its shadows.
  void bind(GLuint program) const;

 private:
  Camera camera_;
  double bias_ = 0, slope_bias_ = 0;
  bool corrected_depth_ = true;
  GLuint fbo_ = 0, depth_ = 0;
};

}  // namespace rl
