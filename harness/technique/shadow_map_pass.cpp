#include "technique/shadow_map_pass.h"

#include <cmath>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "core/error.h"
#include "gl/context.h"
#include "gpu/scene_uniforms.h"
#include "technique/technique.h"

namespace rl {
namespace {

// Texture unit of the map (harness/glsl/shadow_map.glsl): clear of the harness's (0-3, 8) and
// of the techniques' own.
constexpr GLuint kShadowMapUnit = 12;

}  // namespace

ShadowMapPass::ShadowMapPass(const SceneDesc& scene)
    : camera_(light_camera(scene)),
      bias_(scene.shadow_map.bias),
      slope_bias_(scene.shadow_map.slope_bias),
      corrected_depth_(scene.shadow_map.corrected_depth) {
  GlContext::shared();
  glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
  glTextureStorage2D(depth_, 1, GL_DEPTH_COMPONENT32F, size(), size());
  glTextureParameteri(depth_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(depth_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(depth_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(depth_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glCreateFramebuffers(1, &fbo_);
  glNamedFramebufferTexture(fbo_, GL_DEPTH_ATTACHMENT, depth_, 0);
  glNamedFramebufferDrawBuffer(fbo_, GL_NONE);
  glNamedFramebufferReadBuffer(fbo_, GL_NONE);
  const GLenum status = glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("shadow map " + std::to_string(size()) + "x" + std::to_string(size()) +
                  " is incomplete (status " + std::to_string(status) + ")");
}

ShadowMapPass::~ShadowMapPass() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteTextures(1, &depth_);
}

void ShadowMapPass::render(Technique& technique, const FrameInput& frame) const {
  GLint bound_fbo = 0, viewport[4] = {};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound_fbo);
  glGetIntegerv(GL_VIEWPORT, viewport);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, size(), size());
  const float far = 1.0f;
  glClearNamedFramebufferfv(fbo_, GL_DEPTH, 0, &far);
  if (frame.objects) frame.objects->draw_caster(frame.scene, camera_);
  // The relief as its own caster: no shading, no shadows of its own; only the depth it writes.
  EffectSet caster_effects;
  if (corrected_depth_) caster_effects.add(Effect::DepthCorrect);
  const FrameInput caster{.scene = frame.scene,
                          .map = frame.map,
                          .relief = frame.relief,
                          .base = frame.base,
                          .camera = camera_,
                          .effects = caster_effects,
                          .objects = nullptr,
                          .shadow_map = nullptr,
                          .shadow_caster = true};
  technique.render(caster, RenderTarget::Kind::ColorOnly);
  glBindFramebuffer(GL_FRAMEBUFFER, GLuint(bound_fbo));
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}

void ShadowMapPass::bind(GLuint program) const {
  const glm::mat4 view_proj(camera_.projection_matrix() * camera_.view_matrix());
  glProgramUniformMatrix4fv(program, glGetUniformLocation(program, "rl_light_view_projection"), 1,
                            GL_FALSE, glm::value_ptr(view_proj));
  set_uniform(program, "rl_light_eye", camera_.eye);
  set_uniform(program, "rl_light_forward", glm::normalize(camera_.target - camera_.eye));
  set_uniform(program, "rl_light_planes", glm::dvec2(camera_.near_plane, camera_.far_plane));
  set_uniform(program, "rl_shadow_map_bias", bias_);
  set_uniform(program, "rl_shadow_map_slope_bias", slope_bias_);
  set_uniform(program, "rl_shadow_map_texel",
              2 * std::tan(glm::radians(0.5 * camera_.fov_y_deg)) / size());
  glBindTextureUnit(kShadowMapUnit, depth_);
}

}  // namespace rl
