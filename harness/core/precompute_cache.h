#pragma once
// On-disk cache for per-map precomputation (safety radii, cone maps): one binary file per map
// content and option set, under $RELIEFLAB_CACHE_DIR, else $XDG_CACHE_HOME/relieflab, else
// ~/.cache/relieflab. Written to a temporary name and renamed, so a reader never sees half a
// file; any failure to read or write only costs a recompute.
#include <cstddef>
#include <cstdint>
#include <string>

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

}  // namespace rl
