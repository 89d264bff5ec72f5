#include "gl/frame_timer.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <vector>

#include <epoxy/gl.h>

namespace rl {
namespace {

// How long a GPU draws untimed before its frames are timed: a GPU that idled while the CPU
// traced the truth runs at a low clock until the load has lasted a while, and frames timed
// then are several times slower (on an NVIDIA H200 a 0.4 ms frame was timed at 1.4 ms after
// idling). RELIEFLAB_GPU_WARMUP_MS overrides it, to measure how much is needed.
double gpu_warmup_ms() {
  if (const char* env = std::getenv("RELIEFLAB_GPU_WARMUP_MS"); env && *env) {
    char* end = nullptr;
    const double ms = std::strtod(env, &end);
    if (end && *end == '\0' && ms >= 0 && ms <= 60000) return ms;
  }
  return kGpuWarmupMs;
}

// Draws until `ms` of wall time has passed, waiting for each batch, so the GPU is busy all along.
void draw_for(const std::function<void()>& draw, double ms) {
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
  };
  while (elapsed() < ms) {
    for (int i = 0; i < 4; ++i) draw();
    glFinish();
  }
}

}  // namespace

FrameTiming time_frames(const std::function<void()>& draw, int warmup, int frames, bool software) {
  FrameTiming t;
  t.frames = std::max(1, frames);
  for (int i = 0; i < warmup; ++i) draw();
  if (!software) draw_for(draw, gpu_warmup_ms());
  glFinish();
  std::vector<double> ms;
  if (software) {
    t.method = "wall_clock_glfinish";
    for (int i = 0; i < t.frames; ++i) {
      auto start = std::chrono::steady_clock::now();
      draw();
      glFinish();
      auto end = std::chrono::steady_clock::now();
      ms.push_back(std::chrono::duration<double, std::milli>(end - start).count());
    }
  } else {
    t.method = "gpu_timer";
    std::vector<GLuint> queries(t.frames);
    glGenQueries(t.frames, queries.data());
    for (int i = 0; i < t.frames; ++i) {
      glBeginQuery(GL_TIME_ELAPSED, queries[i]);
      draw();
      glEndQuery(GL_TIME_ELAPSED);
    }
    for (int i = 0; i < t.frames; ++i) {
      GLuint64 ns = 0;
      glGetQueryObjectui64v(queries[i], GL_QUERY_RESULT, &ns);
      ms.push_back(ns * 1e-6);
    }
    glDeleteQueries(t.frames, queries.data());
  }
  std::sort(ms.begin(), ms.end());
  t.min_ms = ms.front();
  auto quantile = [&](double q) {
    const double at = q * double(ms.size() - 1);
    const size_t lo = size_t(at);
    const size_t hi = std::min(lo + 1, ms.size() - 1);
    return ms[lo] + (ms[hi] - ms[lo]) * (at - double(lo));
  };
  t.iqr_ms = quantile(0.75) - quantile(0.25);
  t.median_ms =
      ms.size() % 2 ? ms[ms.size() / 2] : 0.5 * (ms[ms.size() / 2 - 1] + ms[ms.size() / 2]);
  return t;
}

}  // namespace rl
