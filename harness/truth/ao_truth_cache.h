#pragma once
// The reference AO of one truth image, kept across runs: hemisphere rays are most of an AO
// scene's truth (tens of millions per view), while a re-run of the same scene and view would
// trace them again to the same answer. Stored like the precomputes (core/precompute_cache.h,
// folder "ao_truth"), keyed by everything that determines the estimate: the truth's identity
// (scene, texture resolution, view, viewport, truth tolerance, measurement version), the map's
// content, the sampling and this estimator's version. Each pixel's entry also holds a hash of
// the exact hit point and normal it was computed at, and is used only where the new trace hits the
// very same point, so a change of the truth's primary hits can only cost a recompute, never a wrong
// AO. Pixels are independent slots: threads fill disjoint pixels with no lock.
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "truth/reference_ao.h"

namespace rl {

struct ReliefMap;

// The content of everything a map's truth traces: the map, and a meta-relief's layers.
uint64_t truth_source_hash(const ReliefMap& map);

class AoTruthCache {
 public:
  // `identity`: the truth's key and anything else that determines its hits and occluders.
  AoTruthCache(const std::string& identity, uint64_t map_content_hash, const AoSampling& sampling,
               size_t pixels);

  // The stored estimate of `pixel` when it was made at exactly `point` about exactly `normal`,
  // else `compute()`, recorded for the next run.
  template <typename Compute>
  AoEstimate estimate(size_t pixel, const glm::dvec3& point, const glm::dvec3& normal,
                      Compute&& compute) {
    const uint64_t key = point_key(point, normal);
    Entry& e = entries_[pixel];
    if (e.point == key) {
      ++reused_;
      return AoEstimate{e.visibility, e.std_error, e.rays};
    }
    const AoEstimate a = compute();
    e = Entry{key, a.visibility, a.std_error, a.rays, 0};
    ++computed_;
    return a;
  }

  // Writes the entries when any was computed (a failed write only costs a recompute).
  void save() const;
  size_t reused() const { return reused_.load(); }
  size_t computed() const { return computed_.load(); }

 private:
  struct Entry {
    uint64_t point = 0;  // hash of the hit point; 0: none stored
    double visibility = 1, std_error = 0;
    int32_t rays = 0, pad = 0;
  };
  static uint64_t point_key(const glm::dvec3& point, const glm::dvec3& normal);

  std::string options_;
  uint64_t map_hash_ = 0;
  std::vector<Entry> entries_;
  std::atomic<size_t> reused_{0}, computed_{0};
};

}  // namespace rl
