#pragma once
// The least depth of a repeating map over a box of texels, in a few lookups: level l holds the
// least depth of each 2^l x 2^l block of texels (the last block of a row or column may be
// narrower). A box is split where it wraps, and each piece is read at the level where it spans
// at most nine blocks a side; a block reaching past the piece only lowers the answer, so the
// answer is never above the box's least depth (what the curved-base truth's sheet needs:
// truth/shell_sheets.h).
#include <vector>

#include "relief/relief_map.h"

namespace rl {

class MinPyramid {
 public:
  explicit MinPyramid(const ReliefMap& map);
  // At most the least depth of texels x0..x1, y0..y1 (inclusive, any integers: they wrap).
  double least(long x0, long x1, long y0, long y1) const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct Level {
    int width = 0, height = 0;
    std::vector<float> depth;
  };
  // The least over x0..x1, y0..y1 within the map (no wrap).
  double least_within(long x0, long x1, long y0, long y1) const;

  int width_ = 0, height_ = 0;
  std::vector<Level> levels_;
};

}  // namespace rl
