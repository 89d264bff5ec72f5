#pragma once
// Headless OpenGL 4.5 core through EGL with no window. Prefers a hardware EGL device (a real
// GPU when one is present), then falls back to Mesa's surfaceless platform (llvmpipe).
#include <string>

namespace rl {

class GlContext {
 public:
  // The process-wide context, created on first use and made current on the calling thread.
  // Every GL resource (textures, buffers, render targets, programs) calls it first.
  static GlContext& shared();

  const std::string& renderer() const { return renderer_; }
  const std::string& version() const { return version_; }
  const std::string& platform() const { return platform_; }  // "device" or "surfaceless"
  // True on software rasterisers, where GL_TIME_ELAPSED is meaningless and frames are
  // timed with glFinish and the wall clock instead.
  bool is_software() const { return software_; }

 private:
  GlContext();
  std::string renderer_, version_, platform_;
  bool software_ = false;
};

}  // namespace rl
