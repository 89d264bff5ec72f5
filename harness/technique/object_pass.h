#pragma once
// Draws a scene's plain triangle-mesh objects (scene/scene_objects.h) into the bound render
// target with the depth test on, before the relief: with depth correction the relief then
// resolves visibility against them per pixel (chapter 5, Figure 5.20). With scene_shadows they
// are drawn into the light's shadow map too, and receive its shadows.
#include <epoxy/gl.h>

#include "gl/render_target.h"
#include "gl/shader_library.h"
#include "gpu/triangle_buffers.h"
#include "scene/scene.h"
#include "scene/scene_objects.h"

namespace rl {

class ShadowMapPass;

class ObjectPass {
 public:
  explicit ObjectPass(const std::vector<SceneObject>& objects);
  ObjectPass(const ObjectPass&) = delete;
  ObjectPass& operator=(const ObjectPass&) = delete;

  bool empty() const { return buffers_.empty(); }
  // Receiving the shadows of `shadows` where given (scene_shadows).
  void draw(const SceneDesc& scene, const Camera& camera, RenderTarget::Kind target,
            const ShadowMapPass* shadows = nullptr) const;
  // Into a shadow map from the light (`light`): depth only.
  void draw_caster(const SceneDesc& scene, const Camera& light) const;

 private:
  void draw_with(const ProgramDesc& program, const SceneDesc& scene, const Camera& camera,
                 const ShadowMapPass* shadows) const;
  TriangleBuffers buffers_;
};

}  // namespace rl
