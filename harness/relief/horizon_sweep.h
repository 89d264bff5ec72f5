#pragma once
// The horizon of a tileable height field along one azimuth, for every texel at once: parallel
// lines one texel apart are swept across the map against the azimuth, and the upper convex hull
// of the profile ahead of the sweep gives each line sample its horizon in amortised constant
// time (Timonen & Westerholm, "Scalable Height Field Self-Shadowing", Eurographics 2010).
//
// A texel centre lies between two lines. Its horizon is exact over its first `near_steps`
// samples (bilinear, one texel apart along its own ray, as the per-texel march takes them);
// beyond them it comes from the tangents from the texel's own point to the two lines' hulls,
// interpolated across the lines. Lines are swept in bundles of 32 strips: a bundle samples its 33
// lines, gathers its texels row by row (reading their heights and near horizons in memory
// order) and sorts them by the sample that resolves them, then builds the lines' hulls from the
// far end, resolving each texel while the hulls it needs are live; so no azimuth's line samples
// are stored whole (about 30 MB at 1024^2). What the interpolation costs in accuracy against
// the per-texel march is measured in tests/test_ambient_occlusion.cpp.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/uninitialized.h"

namespace rl {

// Heights in texel units (x, y and height alike), wrapping like GL_REPEAT.
class TiledHeights {
 public:
  // From the heights of the map's texels, row by row (width x height of them).
  TiledHeights(int width, int height, const float* heights);
  TiledHeights(int width, int height, const std::vector<float>& heights)
      : TiledHeights(width, height, heights.data()) {}
  int width() const { return w_; }
  int height() const { return h_; }
  float at(int x, int y) const { return padded_[size_t(y) * (w_ + 1) + size_t(x)]; }
  // Bilinear at texel-centre coordinates (texel (i, j) at (i, j)), 0 <= x < width and
  // 0 <= y < height: the wrap is already taken.
  float bilinear_wrapped(double x, double y) const {
    const int x0 = int(x), y0 = int(y);
    return bilinear_at(x0, y0, float(x - x0), float(y - y0));
  }
  // Between texel (x0, y0), 0 <= x0 < width, 0 <= y0 < height, and its neighbours at + 1,
  // weighted a across x and b across y.
  float bilinear_at(int x0, int y0, float a, float b) const {
    const float* r0 = &padded_[size_t(y0) * (w_ + 1) + size_t(x0)];
    const float* r1 = r0 + (w_ + 1);
    const float top = r0[0] + (r0[1] - r0[0]) * a;
    const float bottom = r1[0] + (r1[1] - r1[0]) * a;
    return top + (bottom - top) * b;
  }
  // (x, y) moved back by (dx, dy), |dx|, |dy| <= 1, and taken into [0, width) x [0, height):
  // where rounding lands a point on the far edge it wraps to 0, never onto the edge, which
  // bilinear_wrapped would read one row or column past its padding (a 2048^2 sweep crashed so).
  void step_back_wrapped(double& x, double& y, double dx, double dy) const;

 private:
  int w_, h_;
  UninitializedVector<float> padded_;  // (w + 1) x (h + 1): the first row and column repeated
};

struct HorizonSweepOptions {
  int reach = 0;       // texels a line is read ahead of the farthest texel it serves
  int near_steps = 2;  // samples taken exactly along each texel's own ray
};

// Sweeps one height field along azimuth after azimuth, each core keeping its working memory
// (a few MB at 1024^2) from one to the next rather than faulting it in afresh.
class HorizonSweep {
 public:
  HorizonSweep(const TiledHeights& heights, const HorizonSweepOptions& options);
  ~HorizonSweep();
  // tan of the horizon's elevation along (cos phi, sin phi) from every texel centre, at least 0
  // (a horizon below the horizontal counts as open), into `tan_out` (row-major).
  void operator()(double phi, std::vector<float>& tan_out);

 private:
  struct WorkerScratch;
  const TiledHeights& heights_;
  HorizonSweepOptions options_;
  std::vector<std::unique_ptr<WorkerScratch>> scratch_;  // one per parallel_for worker
};

// One azimuth on its own.
void sweep_horizon(const TiledHeights& heights, double phi, const HorizonSweepOptions& options,
                   std::vector<float>& tan_out);

}  // namespace rl
