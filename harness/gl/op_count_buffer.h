#pragma once
// The op-counting render's output: a shader storage buffer at binding 0 that every program in
// its op-counting form (gl/op_counting.h, harness/glsl/gbuffer_outputs.glsl) adds its
// fragments' ops to, per pixel; and the scope in which programs are built in that form.
#include <epoxy/gl.h>

#include "core/op_kinds.h"

namespace rl {

class OpCountBuffer {
 public:
  OpCountBuffer(int width, int height);  // zeroed, the width and height in its first words
  ~OpCountBuffer();
  OpCountBuffer(const OpCountBuffer&) = delete;
  OpCountBuffer& operator=(const OpCountBuffer&) = delete;
  void bind() const;
  // The counts; the caller sets their group_stride, the one its OpCountingScope drew them with.
  PixelOpCounts read_back() const;

 private:
  int width_, height_;
  GLuint buffer_ = 0;
};

// While one is alive, ShaderLibrary builds every program in its op-counting form, counting one
// lockstep group in group_stride^2 (gl/op_counting.h).
class OpCountingScope {
 public:
  explicit OpCountingScope(int group_stride = 1);
  ~OpCountingScope();
  OpCountingScope(const OpCountingScope&) = delete;
  OpCountingScope& operator=(const OpCountingScope&) = delete;
  static bool active();
  static int group_stride();  // of the innermost live scope; 1 when none
};

}  // namespace rl
