#include "gl/frame_timer.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include <epoxy/gl.h>

namespace rl {

FrameTiming time_frames(const std::function<void()>& draw, int warmup, int frames, bool software) {
  FrameTiming t;
  t.frames = std::max(1, frames);
  for (int i = 0; i < warmup; ++i) draw();
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
