#include "core/cost_model.h"

#include "core/columns.h"

namespace rl {
namespace {

const ColumnDeclaration cost_model_columns(
    "metrics (GPU cost model)",
    {{"model_frame_ms", "ms",
      "the frame time the model_gpu's cost model predicts at this viewport, from the pixels, "
      "fragments and lockstep ops counted in this run (core/cost_model.h)"},
     {"model_gpu", "", "the cost model that predicted model_frame_ms (configs/gpu-models/)",
      ColumnKind::Text},
     ColumnSpec{
         "gpu_frame_ms", "ms",
         "time on a GPU: frame_ms_min where the row was timed on one (timing gpu_timer), else "
         "model_frame_ms; the default cost of the Pareto fronts"}
         .reported(),
     {"gpu_frame_ms_source", "", "what gpu_frame_ms is: \"measured\" or \"model <model_gpu>\"",
      ColumnKind::Text}});

}  // namespace

double predict_frame_ms(const CostModel& m, const CostFeatures& f) {
  const double mpx = f.pixels * 1e-6;
  double ms = m.frame_ms + m.pixel_ms * mpx + m.fragment_ms * f.fragments * 1e-6;
  for (int k = 0; k < kOpKinds; ++k) ms += m.op_ms[k] * f.warp_ops_per_px[k] * mpx;
  return ms;
}

std::vector<std::string> cost_model_weight_names() {
  std::vector<std::string> names = {"frame", "pixel", "fragment"};
  for (const char* kind : kOpKindNames) names.emplace_back(kind);
  return names;
}

}  // namespace rl
