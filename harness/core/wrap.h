#pragma once
// A texel index taken into [0, n), as GL_REPEAT wraps it: the one modulo the maps, the
// precomputes and the truths share. No division where the index is already inside (most calls).

namespace rl {

inline int wrap_index(long i, int n) {
  if (i >= 0 && i < n) return int(i);
  const long r = i % n;
  return int(r < 0 ? r + n : r);
}

}  // namespace rl
