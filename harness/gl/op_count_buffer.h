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
  PixelOpCounts read_back() const;

 private:
  int width_, height_;
  GLuint buffer_ = 0;
};

// While one is alive, ShaderLibrary builds every program in its op-counting form.
class OpCountingScope {
 public:
  OpCountingScope();
  ~OpCountingScope();
  OpCountingScope(const OpCountingScope&) = delete;
  OpCountingScope& operator=(const OpCountingScope&) = delete;
  static bool active();
};

}  // namespace rl
