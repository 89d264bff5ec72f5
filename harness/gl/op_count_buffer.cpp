#include "gl/op_count_buffer.h"

#include <algorithm>
#include <vector>

namespace rl {
namespace {

// Words before the pixels (the first two hold the width and height), and words per pixel:
// fragments, then one per kind (harness/glsl/gbuffer_outputs.glsl).
constexpr size_t kHeaderWords = 8, kWordsPerPixel = 8;
static_assert(1 + kOpKinds <= kWordsPerPixel);

std::vector<int> scope_strides;  // of the live scopes, innermost last

}  // namespace

OpCountBuffer::OpCountBuffer(int width, int height) : width_(width), height_(height) {
  std::vector<uint32_t> zeros(kHeaderWords + size_t(width) * height * kWordsPerPixel, 0);
  zeros[0] = uint32_t(width);
  zeros[1] = uint32_t(height);
  glCreateBuffers(1, &buffer_);
  glNamedBufferData(buffer_, GLsizeiptr(zeros.size() * sizeof(uint32_t)), zeros.data(),
                    GL_DYNAMIC_COPY);  // written by the GPU: a READ hint moves it to host memory
}

OpCountBuffer::~OpCountBuffer() {
  glDeleteBuffers(1, &buffer_);
}

void OpCountBuffer::bind() const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer_);
}

PixelOpCounts OpCountBuffer::read_back() const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const size_t pixels = size_t(width_) * height_;
  std::vector<uint32_t> words(kHeaderWords + pixels * kWordsPerPixel);
  glGetNamedBufferSubData(buffer_, 0, GLsizeiptr(words.size() * sizeof(uint32_t)), words.data());
  PixelOpCounts out;
  out.width = width_;
  out.height = height_;
  out.fragments.resize(pixels);
  for (auto& kind : out.ops) kind.resize(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    const uint32_t* px = words.data() + kHeaderWords + i * kWordsPerPixel;
    out.fragments[i] = px[0];
    for (int k = 0; k < kOpKinds; ++k) out.ops[k][i] = px[1 + k];
  }
  return out;
}

OpCountingScope::OpCountingScope(int group_stride) {
  scope_strides.push_back(std::max(group_stride, 1));
}
OpCountingScope::~OpCountingScope() {
  scope_strides.pop_back();
}
bool OpCountingScope::active() {
  return !scope_strides.empty();
}
int OpCountingScope::group_stride() {
  return scope_strides.empty() ? 1 : scope_strides.back();
}

}  // namespace rl
