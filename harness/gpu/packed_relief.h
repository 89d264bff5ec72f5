#pragma once
// The relief map with its AO map packed in (Limberger, Schetinger & Oliveira, Section IV: "the
// AO map can be saved as a separate texture, or stored in the blue channel of the
// (meta-)relief texture. In this case, the R, G, B, and alpha channels store the X and Y
// components of the normal, the AO map, and the depth map, respectively", the normal's Z
// rebuilt). A technique's own copy, bound to unit 20 (harness/glsl/relief_common.glsl,
// RL_AO_PACKED): the search reads its depths, and the shading's normal read brings the AO.
#include <cstddef>

#include <epoxy/gl.h>

#include "relief/relief_map.h"

namespace rl {

class PackedRelief {
 public:
  PackedRelief() = default;
  ~PackedRelief();
  PackedRelief(const PackedRelief&) = delete;
  PackedRelief& operator=(const PackedRelief&) = delete;

  // Uploads `map`'s normals' x and y, its AO (1 where it has none) and its depth, in the
  // relief texture's format (RGBA8 when quantised), bilinear and repeating as GpuRelief.
  void upload(const ReliefMap& map);
  void bind() const;
  size_t bytes() const { return bytes_; }

  static constexpr GLuint kUnit = 20;

 private:
  GLuint texture_ = 0;
  size_t bytes_ = 0;
};

}  // namespace rl
