#include "gpu/gpu_cell_complex.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/gtc/matrix_inverse.hpp>

#include "core/error.h"
#include "gl/context.h"
#include "gpu/scene_uniforms.h"

namespace rl {

uint32_t GpuCellComplex::pack_cell(const CellComplex::Cell& c) {
  const CellProjection& p = c.config.projection;
  // The projection's point has coordinates 0, 0.5 or 1: two bits each as 0, 1, 2.
  const uint32_t point = uint32_t(std::lround(2 * p.point.x)) * 9 +
                         uint32_t(std::lround(2 * p.point.y)) * 3 +
                         uint32_t(std::lround(2 * p.point.z));
  return uint32_t(c.state) | uint32_t(p.type) << 2 | uint32_t(p.axis) << 4 | point << 7 |
         uint32_t(c.config.domain_mask) << 12;
}

GpuCellComplex::GpuCellComplex(const CellComplex& cc) {
  GlContext::shared();
  const int n = cc.grid(), res = cc.resolution();
  std::vector<glm::uvec2> table(size_t(n) * n * n, glm::uvec2(0));
  for (size_t i = 0; i < table.size(); ++i) {
    const CellComplex::Cell& c = cc.cells()[i];
    table[i] = {c.state == CellState::Grey ? pack_cell(c) : uint32_t(c.state),
                uint32_t(std::max(0, c.first_face))};
  }
  glCreateTextures(GL_TEXTURE_3D, 1, &table_);
  glTextureStorage3D(table_, 1, GL_RG32UI, n, n, n);
  glTextureSubImage3D(table_, 0, 0, 0, 0, n, n, n, GL_RG_INTEGER, GL_UNSIGNED_INT, table.data());
  glTextureParameteri(table_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(table_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);

  // Faces per layer: the fewest tiles that keep the layers within the driver's limit.
  GLint max_layers = 2048, max_size = 16384;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  const size_t faces = std::max<size_t>(1, cc.domain_faces().size());
  while ((faces + size_t(tiles_) * tiles_ - 1) / (size_t(tiles_) * tiles_) > size_t(max_layers))
    tiles_ *= 2;
  if (tiles_ * res > max_size)
    throw GlError("cell complex: " + std::to_string(faces) + " domain faces of " +
                  std::to_string(res) + "^2 texels do not fit the driver's array textures");
  const int side = tiles_ * res;
  const int layers = int((faces + size_t(tiles_) * tiles_ - 1) / (size_t(tiles_) * tiles_));
  const size_t layer_texels = size_t(side) * side;
  std::vector<uint16_t> dist16(layer_texels * layers * 2, 0);
  std::vector<uint8_t> normal(layer_texels * layers * 4, 0), color(layer_texels * layers * 4, 0);
  const bool wide = cc.distance_bits() == 16;
  for (size_t f = 0; f < cc.domain_faces().size(); ++f) {
    const size_t layer = f / (size_t(tiles_) * tiles_), tile = f % (size_t(tiles_) * tiles_);
    const int tx = int(tile % tiles_), ty = int(tile / tiles_);
    for (int y = 0; y < res; ++y)
      for (int x = 0; x < res; ++x) {
        const size_t src = f * res * res + size_t(y) * res + x;
        const size_t dst = layer * layer_texels + size_t(ty * res + y) * side + (tx * res + x);
        dist16[2 * dst] = cc.distance()[src];
        dist16[2 * dst + 1] = cc.face_inside()[src] ? (wide ? 65535 : 255) : 0;
        const glm::vec3 nn = cc.normal()[src] * 0.5f + 0.5f;
        const glm::vec3 cl = cc.color()[src];
        for (int k = 0; k < 3; ++k) {
          normal[4 * dst + k] = uint8_t(std::lround(std::clamp(nn[k], 0.0f, 1.0f) * 255));
          color[4 * dst + k] = uint8_t(std::lround(std::clamp(cl[k], 0.0f, 1.0f) * 255));
        }
        normal[4 * dst + 3] = color[4 * dst + 3] = 255;
      }
  }
  auto make_array = [&](GLenum internal, GLenum format, GLenum type, const void* data) {
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &tex);
    glTextureStorage3D(tex, 1, internal, side, side, layers);
    glTextureSubImage3D(tex, 0, 0, 0, 0, side, side, layers, format, type, data);
    // Bilinear within a face; the shader clamps to the face's texel centres (no bleeding into
    // the next tile), like the CPU's CellComplex::sample_distance.
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return tex;
  };
  if (wide) {
    distance_ = make_array(GL_RG16, GL_RG, GL_UNSIGNED_SHORT, dist16.data());
  } else {
    std::vector<uint8_t> dist8(dist16.size());
    for (size_t i = 0; i < dist16.size(); ++i) dist8[i] = uint8_t(dist16[i]);
    distance_ = make_array(GL_RG8, GL_RG, GL_UNSIGNED_BYTE, dist8.data());
  }
  normal_ = make_array(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, normal.data());
  color_ = make_array(GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, color.data());
  bytes_ = cc.gpu_bytes();
}

GpuCellComplex::~GpuCellComplex() {
  const GLuint textures[4] = {table_, distance_, normal_, color_};
  glDeleteTextures(4, textures);
}

void GpuCellComplex::bind() const {
  glBindTextureUnit(4, table_);
  glBindTextureUnit(5, distance_);
  glBindTextureUnit(6, normal_);
  glBindTextureUnit(7, color_);
}

void set_cell_complex_uniforms(GLuint p, const SceneDesc& scene, const Camera& camera,
                               const CellComplex& cells, const GpuCellComplex& gpu) {
  set_texture_space_uniforms(p, scene, camera);
  set_uniform(p, "rl_cell_albedo", glm::dvec3(kCellAlbedo));
  set_cell_table_uniforms(p, cells, gpu);
}

void set_cell_table_uniforms(GLuint p, const CellComplex& cells, const GpuCellComplex& gpu) {
  glProgramUniform1i(p, glGetUniformLocation(p, "rl_cell_n"), cells.grid());
  glProgramUniform1i(p, glGetUniformLocation(p, "rl_cell_res"), cells.resolution());
  glProgramUniform1i(p, glGetUniformLocation(p, "rl_cell_tiles"), gpu.tiles());
}

}  // namespace rl
