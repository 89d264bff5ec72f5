#pragma once
// Wall-clock milliseconds since a steady_clock time point (build and trace timings).
#include <chrono>

namespace rl {

inline double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace rl
