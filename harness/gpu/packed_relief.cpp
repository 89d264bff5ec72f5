#include "gpu/packed_relief.h"

#include <vector>

#include "gpu/gpu_scene.h"

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
  texture_ = make_texture(map.width, map.height, map.quantized ? GL_RGBA8 : GL_RGBA32F, GL_RGBA,
                          &packed[0].x);
  bytes_ = texels * (map.quantized ? 4 : 16);
}

void PackedRelief::bind() const {
  glBindTextureUnit(kUnit, texture_);
}

}  // namespace rl
