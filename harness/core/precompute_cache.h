#pragma once
// On-disk cache for per-map precomputation (safety radii, cone maps): one binary file per map
// content and option set, under $RELIEFLAB_CACHE_DIR, else $XDG_CACHE_HOME/relieflab, else
// ~/.cache/relieflab. Each file carries its own identity and a checksum:
//   "RLPCACHE" | map content hash (u64) | options length (u32) | options text |
//   payload bytes (u64) | FNV-1a of the payload (u64) | payload
// and is used only if all of them match what is asked for, so a truncated, foreign or
// corrupted file is recomputed, never read. The options text names the code that computed it
// too (core/code_digest.h: the harness layers and the calling folder's sources, as built), so a
// rebuilt change to a precompute's code computes it afresh instead of reading what the old code
// made. Files are written to a temporary name and renamed, so a reader never sees half a file;
// a failure to write only costs a recompute.
#include <cstddef>
#include <cstdint>
#include <source_location>
#include <string>
#include <vector>

namespace rl {

// The cache folder in use (see above).
std::string precompute_cache_dir();

// `options` names the algorithm version and every option that changes the answer.
// Fills `out` with exactly `bytes` bytes; false when there is no valid entry.
// `where` is the caller's place in the sources, whose folder's code the entry is keyed by.
bool read_precompute_cache(const std::string& folder, const std::string& options,
                           uint64_t map_content_hash, void* out, size_t bytes,
                           std::source_location where = std::source_location::current());
void write_precompute_cache(const std::string& folder, const std::string& options,
                            uint64_t map_content_hash, const void* data, size_t bytes,
                            std::source_location where = std::source_location::current());

// A per-texel precompute of a width x height map through the cache: `Result` has width,
// height, from_cache and the per-texel vector `data`; `compute()` makes it when the cache has
// none (and it is then stored).
template <typename Result, typename T, typename Compute>
Result cached_precompute(const std::string& folder, const std::string& options, int width,
                         int height, uint64_t map_content_hash, std::vector<T> Result::*data,
                         Compute&& compute,
                         std::source_location where = std::source_location::current()) {
  Result r;
  r.width = width;
  r.height = height;
  (r.*data).resize(size_t(width) * height);
  if (read_precompute_cache(folder, options, map_content_hash, (r.*data).data(),
                            (r.*data).size() * sizeof(T), where)) {
    r.from_cache = true;
    return r;
  }
  r = compute();
  write_precompute_cache(folder, options, map_content_hash, (r.*data).data(),
                         (r.*data).size() * sizeof(T), where);
  return r;
}

}  // namespace rl
