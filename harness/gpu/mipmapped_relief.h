#pragma once
// A relief map's normals and depths with a full mip chain, for techniques that read them at the
// pixel's footprint (chapter 5, "Texture filtering and mip-mapping": "both normal and depth
// components are mip-mapped to lower resolutions"). Each level averages 2 x 2 texels of the one
// above (the driver's glGenerateTextureMipmap): depths and encoded normals alike, which is what
// regular mip-mapping does to a relief map. The shared relief texture (GpuRelief) keeps a
// single level, the surface the truth reconstructs; this is a technique's own copy, bound to
// unit 9 (harness/glsl/relief_common.glsl, RL_MIPMAP). The same for the colour map alone
// (Baboud & Decoret 2006, Section 6: "mipmapping for the color texture"), bound to unit 19
// (RL_COLOR_MIPMAP).
#include <cstddef>

#include <epoxy/gl.h>

#include "relief/relief_map.h"

namespace rl {

// Levels of a full mip chain down to 1 x 1, and the texels of all of them times `texel_bytes`.
int mip_levels(int width, int height);
size_t mip_chain_bytes(int width, int height, size_t texel_bytes);

class MipmappedRelief {
 public:
  enum class Channel { Relief, Color };
  explicit MipmappedRelief(Channel channel = Channel::Relief) : channel_(channel) {}
  ~MipmappedRelief();
  MipmappedRelief(const MipmappedRelief&) = delete;
  MipmappedRelief& operator=(const MipmappedRelief&) = delete;

  // Uploads `map`'s relief or colour texels (RGBA8 when it is quantised, else RGBA32F, as
  // GpuRelief) and builds their mip chain down to 1 x 1; trilinear, repeating.
  void upload(const ReliefMap& map);
  void bind() const;
  // Every level's texels.
  size_t bytes() const { return bytes_; }
  int levels() const { return levels_; }

  static constexpr GLuint kUnit = 9;
  static constexpr GLuint kColorUnit = 19;

 private:
  Channel channel_;
  GLuint texture_ = 0;
  int levels_ = 0;
  size_t bytes_ = 0;
};

}  // namespace rl
