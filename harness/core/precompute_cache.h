#pragma once
// On-disk cache for per-map precomputation (safety radii, cone maps): one binary file per map
// content and option set, under $RELIEFLAB_CACHE_DIR, else $XDG_CACHE_HOME/relieflab, else
// ~/.cache/relieflab. Written to a temporary name and renamed, so a reader never sees half a
// file; any failure to read or write only costs a recompute.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rl {

// File name for a precompute of a map: `options` names the algorithm version and every option
// that changes the answer.
std::string precompute_cache_key(const std::string& options, uint64_t map_content_hash);

// Fills `out` with exactly `bytes` bytes from folder/key.bin; false when the file is absent or
// of another size.
bool read_precompute_cache(const std::string& folder, const std::string& key, void* out,
                           size_t bytes);
void write_precompute_cache(const std::string& folder, const std::string& key, const void* data,
                            size_t bytes);

// A per-texel precompute of a width x height map through the cache: `Result` has width,
// height, from_cache and the per-texel vector `data`; `compute()` makes it when the cache has
// none (and it is then stored).
template <typename Result, typename T, typename Compute>
Result cached_precompute(const std::string& folder, const std::string& options, int width,
                         int height, uint64_t map_content_hash, std::vector<T> Result::*data,
                         Compute&& compute) {
  const std::string key = precompute_cache_key(options, map_content_hash);
  Result r;
  r.width = width;
  r.height = height;
  (r.*data).resize(size_t(width) * height);
  if (read_precompute_cache(folder, key, (r.*data).data(), (r.*data).size() * sizeof(T))) {
    r.from_cache = true;
    return r;
  }
  r = compute();
  write_precompute_cache(folder, key, (r.*data).data(), (r.*data).size() * sizeof(T));
  return r;
}

}  // namespace rl
