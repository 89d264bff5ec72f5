#pragma once
// Meta-relief texture mapping (Limberger, Schetinger & Oliveira, Section III): finer relief
// layers added on top of coarser ones. Layer i is a relief map of its own resolution, repeated
// `tiling` times per unit of the base's texture coordinate (fractional tilings such as 5.5 and
// 14.5, Figure 8, included); the surface is
//   depth(u, v)  = sum_i w_di d_i(t_i u, t_i v) / sum_i w_di                          (Eq. 2)
//   normal(u, v) = normalize(sum_i w_ni n_i(t_i u, t_i v)) (Eq. 1, normalised afterwards)
// with d_i, n_i each layer's GL_LINEAR samples (n_i decoded and normalised like the shaders
// do). The shaders evaluate the same per fetch (harness/glsl/relief_common.glsl,
// rl_relief_texel) or sample a bake of it (bake_meta_relief).
//
// Within the cell that every layer's texel-centre grid leaves between its crease lines (the
// union of the grids), each d_i is bilinear in (u, v), so the combined depth is one bilinear
// patch per union cell: truth/meta_relief_truth.h traces it exactly.
#include <memory>
#include <vector>

#include "relief/relief_map.h"

namespace rl {

struct MetaLayer {
  ReliefMap map;             // normals + depth (its colour is unused but for layer 0's)
  double tiling = 1;         // repeats per unit of the base's texture coordinate
  double weight_normal = 1;  // w_n (non-negative)
  double weight_depth = 1;   // w_d (non-negative)
};

class MetaRelief {
 public:
  // Throws std::invalid_argument when a weight is negative or not finite, the normal or the
  // depth weights sum to zero, a tiling is not positive and finite, or there is no layer.
  explicit MetaRelief(std::vector<MetaLayer> layers);

  const std::vector<MetaLayer>& layers() const { return layers_; }
  // Weights over their sums: what Eqs. 1 and 2 multiply each layer by.
  double normal_share(size_t i) const { return layers_[i].weight_normal / sum_normal_; }
  double depth_share(size_t i) const { return layers_[i].weight_depth / sum_depth_; }

  double depth(double u, double v) const;  // Eq. 2
  // rgb: the Eq. 1 normal encoded * 0.5 + 0.5 (unit length); a: the Eq. 2 depth.
  glm::dvec4 relief(double u, double v) const;
  // Bounds of the depth: sum of each layer's min (max) times its share.
  double min_depth() const { return min_depth_; }
  double max_depth() const { return max_depth_; }
  // Texels per unit of base texture coordinate of the finest layer along u and v.
  double finest_texels() const;

 private:
  std::vector<MetaLayer> layers_;
  double sum_normal_ = 0, sum_depth_ = 0;
  double min_depth_ = 0, max_depth_ = 0;
};

// The combination sampled at the texel centres of a width x height map: normals and depth by
// Eqs. 1-2, colour from layer 0 or `color` (bilinear, at the base's coordinates). A bake at any
// size; with integer tilings whose grids all fall on the bake's texel centres it is exact,
// otherwise the bake's bilinear reconstruction and its tile seam (a fractional tiling does not
// repeat over one base tile) differ from the combination: what a bake costs in accuracy. `color`:
// the map whose colour the bake samples (default: layer 0's).
ReliefMap bake_meta_relief(const MetaRelief& meta, int width, int height,
                           const ReliefMap* color = nullptr);

// Combines the layers' AO maps (visibility, each at its layer's resolution, wrapping) into one
// map at width x height on the base's coordinates, sampled bilinearly at each layer's tiling:
// the product of the visibilities or their minimum (Section IV-A's two alternatives).
enum class AoCombine { Product, Min };
// The combined visibility at (u, v): what the shader computes per fetch
// (ambient_occlusion.glsl, rl_stored_ao) and combine_ao_maps() stores per texel.
double combined_ao(const MetaRelief& meta, const std::vector<std::vector<float>>& layer_ao,
                   double u, double v, AoCombine how);
std::vector<float> combine_ao_maps(const MetaRelief& meta,
                                   const std::vector<std::vector<float>>& layer_ao, int width,
                                   int height, AoCombine how);

}  // namespace rl
