#include "truth/min_pyramid.h"

#include <algorithm>
#include <limits>

namespace rl {

MinPyramid::MinPyramid(const ReliefMap& map) : width_(map.width), height_(map.height) {
  Level base{map.width, map.height, map.depths()};
  levels_.push_back(std::move(base));
  while (levels_.back().width > 1 || levels_.back().height > 1) {
    const Level& fine = levels_.back();
    Level coarse{(fine.width + 1) / 2, (fine.height + 1) / 2, {}};
    coarse.depth.resize(size_t(coarse.width) * size_t(coarse.height));
    for (int y = 0; y < coarse.height; ++y)
      for (int x = 0; x < coarse.width; ++x) {
        float least = std::numeric_limits<float>::infinity();
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) {
            const int fx = std::min(2 * x + dx, fine.width - 1),
                      fy = std::min(2 * y + dy, fine.height - 1);
            least = std::min(least, fine.depth[size_t(fy) * size_t(fine.width) + size_t(fx)]);
          }
        coarse.depth[size_t(y) * size_t(coarse.width) + size_t(x)] = least;
      }
    levels_.push_back(std::move(coarse));
  }
}

double MinPyramid::least_within(long x0, long x1, long y0, long y1) const {
  const long span = std::max(x1 - x0, y1 - y0) + 1;
  size_t level = 0;
  while (level + 1 < levels_.size() && (long(8) << level) < span) ++level;
  const Level& l = levels_[level];
  double least = std::numeric_limits<double>::infinity();
  for (long y = y0 >> level; y <= (y1 >> level); ++y)
    for (long x = x0 >> level; x <= (x1 >> level); ++x)
      least = std::min(least, double(l.depth[size_t(y) * size_t(l.width) + size_t(x)]));
  return least;
}

double MinPyramid::least(long x0, long x1, long y0, long y1) const {
  if (x1 - x0 + 1 >= width_) x0 = 0, x1 = width_ - 1;
  if (y1 - y0 + 1 >= height_) y0 = 0, y1 = height_ - 1;
  // Shift the box's start into the map; a box then wraps at most once on each axis.
  const long sx = (x0 % width_ + width_) % width_ - x0,
             sy = (y0 % height_ + height_) % height_ - y0;
  x0 += sx, x1 += sx, y0 += sy, y1 += sy;
  double least = std::numeric_limits<double>::infinity();
  for (const auto& [ax, bx] :
       {std::pair{x0, std::min(x1, long(width_) - 1)}, std::pair{long(0), x1 - long(width_)}}) {
    if (bx < ax) continue;
    for (const auto& [ay, by] :
         {std::pair{y0, std::min(y1, long(height_) - 1)}, std::pair{long(0), y1 - long(height_)}}) {
      if (by < ay) continue;
      least = std::min(least, least_within(ax, bx, ay, by));
    }
  }
  return least;
}

}  // namespace rl
