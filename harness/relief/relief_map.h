#pragma once
// A single-layer relief map exactly as the GPU sees it: RGBA = encoded tangent-space normal
// (rgb in [0,1], z out of the surface) and depth in alpha (0 = top, 1 = bottom), plus a
// colour map of the same size. The CPU samplers below reproduce GL_LINEAR + GL_REPEAT, so
// the truth reconstructs the very surface the shaders sample.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace rl {

struct ReliefMap {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> relief;  // rgb: normal * 0.5 + 0.5, a: depth; row 0 is v = 0.5 / height
  std::vector<glm::vec4> color;   // rgb colour (linear), a = 1
  bool quantized = false;         // every channel holds an exact multiple of 1/255

  size_t index(int x, int y) const;  // wraps like GL_REPEAT
  float depth_texel(int x, int y) const { return relief[index(x, y)].a; }
  // Bilinear samples at texture coordinate (u, v), GL_LINEAR + GL_REPEAT semantics.
  double sample_depth(double u, double v) const;
  glm::dvec4 sample_relief(double u, double v) const;
  glm::dvec4 sample_color(double u, double v) const;
  float min_depth() const;
  float max_depth() const;
  // Hash of the size and contents: keys precompute caches and result rows.
  uint64_t content_hash() const;
  size_t gpu_bytes() const;  // relief + colour textures as uploaded
};

// Decodes an encoded normal like the shaders do: normalize(rgb * 2 - 1).
glm::dvec3 decode_normal(const glm::dvec4& rgba);

// Rounds every channel to the nearest multiple of 1/255 (8-bit textures, as in the papers).
void quantize_8bit(ReliefMap& map);
// Filtered resize of depth, normals (renormalised) and colour to width x height.
ReliefMap resample(const ReliefMap& map, int width, int height);
// Replaces the normals with those of the heightfield itself, by central differences.
// `depth_per_texel` = world relief depth / world texel width (the slope scale).
void normals_from_depth(ReliefMap& map, double depth_per_texel);

}  // namespace rl
