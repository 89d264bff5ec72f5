#include "gpu/mipmapped_relief.h"

#include <algorithm>

namespace rl {

int mip_levels(int width, int height) {
  int levels = 1;
  for (int side = std::max(width, height); side > 1; side /= 2) ++levels;
  return levels;
}

size_t mip_chain_bytes(int width, int height, size_t texel_bytes) {
  size_t bytes = 0;
  for (int l = 0; l < mip_levels(width, height); ++l)
    bytes += size_t(std::max(1, width >> l)) * size_t(std::max(1, height >> l)) * texel_bytes;
  return bytes;
}

MipmappedRelief::~MipmappedRelief() {
  if (texture_) glDeleteTextures(1, &texture_);
}

void MipmappedRelief::upload(const ReliefMap& map) {
  if (texture_) glDeleteTextures(1, &texture_);
  const bool color = channel_ == Channel::Color;
  const int width = color ? map.color_w() : map.width, height = color ? map.color_h() : map.height;
  levels_ = mip_levels(width, height);
  const GLenum format = map.quantized ? GL_RGBA8 : GL_RGBA32F;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
  glTextureStorage2D(texture_, levels_, format, width, height);
  glTextureSubImage2D(texture_, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT,
                      color ? map.color.data() : map.relief.data());
  glGenerateTextureMipmap(texture_);
  glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture_, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(texture_, GL_TEXTURE_WRAP_T, GL_REPEAT);
  bytes_ = mip_chain_bytes(width, height, map.quantized ? 4 : 16);
}

void MipmappedRelief::bind() const {
  glBindTextureUnit(channel_ == Channel::Color ? kColorUnit : kUnit, texture_);
}

}  // namespace rl
