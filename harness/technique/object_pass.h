#pragma once
// Draws a scene's plain triangle-mesh objects (scene/scene_objects.h) into the bound render
// target with the depth test on, before the relief: with depth correction the relief then
// resolves visibility against them per pixel (chapter 5, Figure 5.20).
#include <epoxy/gl.h>

#include "gl/render_target.h"
#include "gpu/triangle_buffers.h"
#include "scene/scene.h"
#include "scene/scene_objects.h"

namespace rl {

class ObjectPass {
 public:
  explicit ObjectPass(const std::vector<SceneObject>& objects);
  ObjectPass(const ObjectPass&) = delete;
  ObjectPass& operator=(const ObjectPass&) = delete;

  bool empty() const { return buffers_.empty(); }
  void draw(const SceneDesc& scene, const Camera& camera, RenderTarget::Kind target) const;

 private:
  TriangleBuffers buffers_;
};

}  // namespace rl
