#include "truth/ao_truth_cache.h"

#include <cstdio>

#include "core/hash.h"
#include "core/precompute_cache.h"
#include "relief/meta_relief.h"
#include "relief/relief_map.h"

namespace rl {
namespace {

// Bump when reference_ao's answer for the same hit and sampling changes.
constexpr int kReferenceAoVersion = 2;
constexpr const char* kFolder = "ao_truth";

}  // namespace

AoTruthCache::AoTruthCache(const std::string& identity, uint64_t map_content_hash,
                           const AoSampling& sampling, size_t pixels)
    : map_hash_(map_content_hash), entries_(pixels) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "|reference_ao v%d samples=%d stderr_target=%.17g",
                kReferenceAoVersion, sampling.max_samples, sampling.stderr_target);
  options_ = identity + buf;
  if (!read_precompute_cache(kFolder, options_, map_hash_, entries_.data(),
                             entries_.size() * sizeof(Entry)))
    entries_.assign(pixels, Entry{});
}

uint64_t truth_source_hash(const ReliefMap& map) {
  uint64_t h = map.content_hash();
  if (!map.meta) return h;
  for (size_t i = 0; i < map.meta->layers().size(); ++i) {
    const MetaLayer& layer = map.meta->layers()[i];
    const uint64_t layer_hash = layer.map.content_hash();
    const double tiling = layer.tiling, share = map.meta->depth_share(i);
    h = fnv1a64(&layer_hash, sizeof layer_hash, h);
    h = fnv1a64(&tiling, sizeof tiling, h);
    h = fnv1a64(&share, sizeof share, h);
  }
  return h;
}

uint64_t AoTruthCache::point_key(const glm::dvec3& point, const glm::dvec3& normal) {
  const uint64_t h = fnv1a64(&normal, sizeof normal, fnv1a64(&point, sizeof point));
  return h == 0 ? 1 : h;  // 0 marks an empty slot
}

void AoTruthCache::save() const {
  if (computed_.load() == 0) return;
  write_precompute_cache(kFolder, options_, map_hash_, entries_.data(),
                         entries_.size() * sizeof(Entry));
}

}  // namespace rl
