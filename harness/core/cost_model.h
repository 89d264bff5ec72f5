#pragma once
// A GPU cost model: a named GPU's frame time predicted from counts that every renderer makes,
// llvmpipe included -- the viewport's pixels, the fragments shaded (metrics/fragment_cost.h) and
// the ops each 8 x 4 lockstep group executes, by kind (metrics/op_cost.h). Linear and non-negative:
//
//   model_frame_ms = frame + pixel * Mpx + fragment * Mfragments + sum_k op_k * Mops_k
//
// with Mpx the viewport's pixels, Mfragments the fragments shaded and Mops_k the lockstep ops of
// kind k over the frame, all in millions. The weights are data, fitted per GPU to measured rows
// (scripts/fit-cost-model.py; configs/gpu-models/*.toml; results/gpu-model/ has the fit and its
// cross-validation).
#include <array>
#include <string>
#include <vector>

#include "core/op_kinds.h"

namespace rl {

struct CostModel {
  std::string name;  // the file's stem, e.g. "nvidia-h200": the row's model_gpu
  std::string gpu;   // the GPU it predicts, e.g. "NVIDIA H200"
  double frame_ms = 0, pixel_ms = 0, fragment_ms = 0;  // ms per frame, per Mpx, per Mfragment
  std::array<double, kOpKinds> op_ms{};                // ms per million lockstep ops of a kind
};

// What one frame of a cell counts, as the model reads it.
struct CostFeatures {
  double pixels = 0;     // the viewport's
  double fragments = 0;  // shaded, every pass
  std::array<double, kOpKinds> warp_ops_per_px{};
};

// NaN when a count is missing (NaN).
double predict_frame_ms(const CostModel& model, const CostFeatures& features);

// The weights' names in a model file's [weights] table, in CostModel's order: "frame", "pixel",
// "fragment", then each op kind's name (core/op_kinds.h).
std::vector<std::string> cost_model_weight_names();

}  // namespace rl
