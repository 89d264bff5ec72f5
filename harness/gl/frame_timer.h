#pragma once
// Frame timing: the median of repeated frames after warm-up. On a GPU each frame is timed by
// a GL_TIME_ELAPSED query; on a software rasteriser (llvmpipe), where that query measures
// nothing useful, by the wall clock around the draw and a glFinish.
#include <functional>
#include <string>

namespace rl {

struct FrameTiming {
  double median_ms = 0;
  double min_ms = 0;
  // Spread: interquartile range (linear interpolation between order statistics). A median
  // whose IQR overlaps another row's does not rank them; fetches do.
  double iqr_ms = 0;
  int frames = 0;
  std::string method;  // "gpu_timer" or "wall_clock_glfinish"
};

// On a GPU, after the `warmup` frames, frames are drawn untimed for this long (wall clock) so that
// the GPU's clock has risen from idle before any frame is timed.
inline constexpr double kGpuWarmupMs = 250;

// Times `frames` draws after `warmup` untimed ones (and, on a GPU, kGpuWarmupMs of drawing).
FrameTiming time_frames(const std::function<void()>& draw, int warmup, int frames, bool software);

}  // namespace rl
