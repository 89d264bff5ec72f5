#pragma once
// Offscreen render targets: the G-buffer (five RGBA32F attachments + depth, matching
// core/gbuffer.h) for measuring, or a single RGBA8 colour target for timing. A G-buffer target
// also counts what every fragment shaded into it fetched (core/fragment_counts.h) on image
// units 3-7 (gbuffer_outputs.glsl), bound by bind_and_clear().
#include <epoxy/gl.h>

#include "core/fragment_counts.h"
#include "core/gbuffer.h"

namespace rl {

class RenderTarget {
 public:
  enum class Kind { GBuffer, ColorOnly };
  RenderTarget(int width, int height, Kind kind);
  ~RenderTarget();
  RenderTarget(const RenderTarget&) = delete;
  RenderTarget& operator=(const RenderTarget&) = delete;

  void bind_and_clear();
  void read_back(GBuffer& out) const;  // GBuffer kind only
  // What the fragments shaded since bind_and_clear() fetched, per pixel (GBuffer kind only).
  void read_back_costs(FragmentCounts& out) const;
  int width() const { return width_; }
  int height() const { return height_; }
  Kind kind() const { return kind_; }

 private:
  int width_, height_;
  Kind kind_;
  GLuint fbo_ = 0, depth_ = 0;
  GLuint color_[5] = {0, 0, 0, 0, 0};
  // r32ui: fragments, fetch sum, fetch max, iteration sum, iteration max.
  static constexpr int kCostImages = 5, kFirstCostImageUnit = 3;
  GLuint costs_[kCostImages] = {};
  int attachments_ = 0;
};

}  // namespace rl
