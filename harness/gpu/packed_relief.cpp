#include "gpu/packed_relief.h"

#include <vector>

namespace rl {

PackedRelief::~PackedRelief() {
  if (texture_) glDeleteTextures(1, &texture_);
}

void PackedRelief::upload(const ReliefMap& map) {
  if (texture_) glDeleteTextures(1, &texture_);
  const size_t texels = size_t(map.width) * map.height;
  std::vector<glm::vec4> packed(texels);
  for (size_t i = 0; i < texels; ++i) {
    const glm::vec4& r = map.relief[i];  // normal * 0.5 + 0.5, depth
    const float ao = map.ambient_visibility.empty() ? 1.0f : map.ambient_visibility[i];
    packed[i] = glm::vec4(r.x, r.y, ao, r.a);
  }
  const GLenum format = map.quantized ? GL_RGBA8 : GL_RGBA32F;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
  glTextureStorage2D(texture_, 1, format, map.width, map.height);
  glTextureSubImage2D(texture_, 0, 0, 0, map.width, map.height, GL_RGBA, GL_FLOAT, packed.data());
  glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture_, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(texture_, GL_TEXTURE_WRAP_T, GL_REPEAT);
  bytes_ = texels * (map.quantized ? 4 : 16);
}

void PackedRelief::bind() const {
  glBindTextureUnit(kUnit, texture_);
}

}  // namespace rl
