#pragma once
// A single-layer relief map exactly as the GPU sees it: RGBA = encoded tangent-space normal
// (rgb in [0,1], z out of the surface) and depth in alpha (0 = top, 1 = bottom), plus a
// colour map of the same size. The CPU samplers below reproduce GL_LINEAR + GL_REPEAT, so
// the truth reconstructs the very surface the shaders sample.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace rl {

class MetaRelief;         // relief/meta_relief.h
class CellComplex;        // relief/cell_complex.h
struct HeightfieldFaces;  // relief/heightfield_faces.h

// Several depth layers per texel (Policarpo & Oliveira 2006, Section 3): every crossing of
// a vertical bake ray with a closed surface, sorted top to bottom, so a point at depth d is
// inside the surface when an odd number of layers lie above it. Layer l of texel i is at
// [l * texels + i]; unused layers have depth 1 (the paper's convention). Normals are unit
// tangent-space normals (z out of the base) pointing out of the solid: up on even layers
// (where a downward ray enters), down on odd ones. Sampled with GL_NEAREST (Section 6).
struct LayerStack {
  int count = 0;  // layers per texel (0: the map is a heightfield); at most kMaxLayers
  std::vector<float> depth;
  std::vector<glm::vec3> normal;
  std::vector<glm::vec3> color;
  // What the bake could not keep: texels whose ray crossed more surfaces than `count`, and
  // the most crossings any texel's ray had (the pattern's depth complexity).
  long overflow_texels = 0;
  int max_crossings = 0;
  // Crossings whose mesh winding disagreed with their order (an even crossing facing down, an
  // odd one facing up): 0 for a closed, consistently wound mesh. They are stored oriented by
  // the order, which is what the inside test needs.
  long misoriented_crossings = 0;
  // Texels whose ray crossed the surface an odd number of times: an open or non-manifold mesh
  // (the Utah teapot's spout and rim); a closed mesh has none. An impostor's bake drops the
  // deepest crossing there (a hole rather than a solid curtain below the last layer).
  long odd_texels = 0;
  // What storing the normals as the paper does cost (Figure 5: x and y in 8 bits, z rebuilt on
  // the layer's side; quantize_8bit): the angle between each surface texel's normal before and
  // after, mean and largest, in degrees (0 before quantisation).
  double normal_storage_err_mean_deg = 0, normal_storage_err_max_deg = 0;

  static constexpr int kMaxLayers = 8;
  bool empty() const { return count == 0; }
  // How many layers texel i uses (depth < 1).
  int used(size_t texel) const;
};

// The floor under a multilayer map (depth 1, facing up) where a scene asks for a solid one,
// and the colour of the empty texels of its top-layer view.
inline const glm::vec3 kLayeredFloorColor(0.78f, 0.74f, 0.70f);

struct ReliefMap {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> relief;  // rgb: normal * 0.5 + 0.5, a: depth; row 0 is v = 0.5 / height
  std::vector<glm::vec4> color;   // rgb colour (linear), a = 1
  // The colour map's own size, where it has one (Baboud & Decoret, Section 4.3: "depth and
  // color textures can therefore have different resolutions"); 0: the relief's.
  int color_width = 0, color_height = 0;
  bool quantized = false;  // every channel holds an exact multiple of 1/255
  LayerStack layers;       // non-height-field maps: their layers; `relief` is the top one
  // The colour of a layered map's solid floor (the scene's floor_color), where it is drawn.
  glm::vec3 floor_color = kLayeredFloorColor;
  // The texture-space AO map (relief/ao_map.h), only where a scene asks for ambient_occlusion:
  // visibility in [0, 1] per texel, uploaded 8-bit when the map is quantised.
  std::vector<float> ambient_visibility;
  // A meta-relief (relief/meta_relief.h): the surface is the combination of its layers and
  // `relief` holds its bake; null for a plain map.
  std::shared_ptr<const MetaRelief> meta;
  // Its layers' AO maps (each at its layer's size), where the scene combines them by product or
  // minimum: the shader combines them per fetch when it combines the layers.
  std::vector<std::vector<float>> meta_ambient_visibility;
  // A mesh encoded as a cubic cell complex (relief/cell_complex.h): the GPU gets the complex;
  // `relief` and `color` are a flat placeholder.
  std::shared_ptr<const CellComplex> cells;
  // An object from several heightfields (relief/heightfield_faces.h): one map per cube face;
  // `relief` and `color` are the top face's.
  std::shared_ptr<const HeightfieldFaces> faces;

  size_t index(int x, int y) const;  // wraps like GL_REPEAT
  int color_w() const { return color_width > 0 ? color_width : width; }
  int color_h() const { return color_height > 0 ? color_height : height; }
  float depth_texel(int x, int y) const { return relief[index(x, y)].a; }
  // Bilinear samples at texture coordinate (u, v), GL_LINEAR + GL_REPEAT semantics.
  double sample_depth(double u, double v) const;
  glm::dvec4 sample_relief(double u, double v) const;
  // The same with GL_CLAMP_TO_EDGE semantics: the coordinate clamped to the edge texels'
  // centres (a map that does not repeat, e.g. a heightfield object's face).
  glm::dvec4 sample_relief_clamped(double u, double v) const;
  glm::dvec4 sample_color(double u, double v) const;
  // The surface the map stands for: its own samples, or a meta-relief's combination (Eqs. 1-2)
  // of which `relief` is only the bake. What the truth traces and shades with.
  double surface_depth(double u, double v) const;
  glm::dvec4 surface_relief(double u, double v) const;
  float min_depth() const;
  float max_depth() const;
  // The depths alone (relief's alpha), row-major, 4 bytes a texel: for loops that read many of
  // them, where the 16-byte texels would waste three quarters of every cache line.
  std::vector<float> depths() const;
  // Hash of the size and contents: keys precompute caches and result rows.
  uint64_t content_hash() const;
  // Relief + colour (+ AO) textures as uploaded; with `meta_layers`, a meta-relief's layer
  // textures (combined per fetch) in place of its bake.
  size_t gpu_bytes(bool meta_layers = false) const;
};

// Decodes an encoded normal like the shaders do: normalize(rgb * 2 - 1).
glm::dvec3 decode_normal(const glm::dvec4& rgba);

// A layer's normal as the shaders rebuild it from its stored x and y (Section 3: z =
// sqrt(max(0, 1 - x^2 - y^2))), negative on odd (back) layers (Appendix A).
glm::vec3 layer_normal_from_xy(float x, float y, int layer);

// Rounds every channel to the nearest multiple of 1/255 (8-bit textures, as in the papers).
void quantize_8bit(ReliefMap& map);
// Filtered resize of depth, normals (renormalised) and colour to width x height.
ReliefMap resample(const ReliefMap& map, int width, int height);
// Replaces the normals with those of the heightfield itself, by central differences.
// `depth_per_texel` = world relief depth / world texel width (the slope scale).
void normals_from_depth(ReliefMap& map, double depth_per_texel);

}  // namespace rl
