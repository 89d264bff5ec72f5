#include "gl/render_target.h"

#include <string>

#include "core/error.h"
#include "gl/context.h"

namespace rl {

RenderTarget::RenderTarget(int width, int height, Kind kind)
    : width_(width), height_(height), kind_(kind) {
  GlContext::shared();
  attachments_ = kind == Kind::GBuffer ? 5 : 1;
  glCreateFramebuffers(1, &fbo_);
  glCreateTextures(GL_TEXTURE_2D, attachments_, color_);
  for (int i = 0; i < attachments_; ++i) {
    glTextureStorage2D(color_[i], 1, kind == Kind::GBuffer ? GL_RGBA32F : GL_RGBA8, width, height);
    glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0 + i, color_[i], 0);
  }
  glCreateRenderbuffers(1, &depth_);
  glNamedRenderbufferStorage(depth_, GL_DEPTH_COMPONENT32F, width, height);
  glNamedFramebufferRenderbuffer(fbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum buffers[5] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                             GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4};
  glNamedFramebufferDrawBuffers(fbo_, attachments_, buffers);
  if (kind == Kind::GBuffer) {
    glCreateTextures(GL_TEXTURE_2D, kCostImages, costs_);
    for (GLuint t : costs_) glTextureStorage2D(t, 1, GL_R32UI, width, height);
  }
  GLenum status = glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("render target " + std::to_string(width) + "x" + std::to_string(height) +
                  " is incomplete (status " + std::to_string(status) + ")");
}

RenderTarget::~RenderTarget() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteTextures(attachments_, color_);
  glDeleteRenderbuffers(1, &depth_);
  if (kind_ == Kind::GBuffer) glDeleteTextures(kCostImages, costs_);
}

void RenderTarget::bind_and_clear() {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
  const float zero[4] = {0, 0, 0, 0};
  for (int i = 0; i < attachments_; ++i) glClearNamedFramebufferfv(fbo_, GL_COLOR, i, zero);
  const float one = 1.0f;
  glClearNamedFramebufferfv(fbo_, GL_DEPTH, 0, &one);
  if (kind_ != Kind::GBuffer) return;
  const GLuint zero_u = 0;
  for (int i = 0; i < kCostImages; ++i) {
    glClearTexImage(costs_[i], 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero_u);
    glBindImageTexture(kFirstCostImageUnit + i, costs_[i], 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  }
}

void RenderTarget::read_back(GBuffer& out) const {
  if (kind_ != Kind::GBuffer) throw GlError("read_back needs a G-buffer render target");
  out.resize(width_, height_);
  std::vector<glm::vec4>* dst[5] = {&out.color, &out.position, &out.normal, &out.hit, &out.aux};
  const GLsizei bytes = static_cast<GLsizei>(out.size() * sizeof(glm::vec4));
  for (int i = 0; i < 5; ++i)
    glGetTextureImage(color_[i], 0, GL_RGBA, GL_FLOAT, bytes, dst[i]->data());
}

void RenderTarget::read_back_costs(FragmentCounts& out) const {
  if (kind_ != Kind::GBuffer) throw GlError("read_back_costs needs a G-buffer render target");
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  out.resize(width_, height_);
  std::vector<uint32_t>* dst[kCostImages] = {&out.fragments, &out.fetch_sum, &out.fetch_max,
                                             &out.iteration_sum, &out.iteration_max};
  const GLsizei bytes = static_cast<GLsizei>(out.fragments.size() * sizeof(uint32_t));
  for (int i = 0; i < kCostImages; ++i)
    glGetTextureImage(costs_[i], 0, GL_RED_INTEGER, GL_UNSIGNED_INT, bytes, dst[i]->data());
}

}  // namespace rl
