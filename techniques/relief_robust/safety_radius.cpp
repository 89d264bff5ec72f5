#include "safety_radius.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/precompute_cache.h"
#include "radius_lines.h"

namespace rl {

int SafetyRadii::zero_count() const {
  return int(std::count(radius.begin(), radius.end(), uint8_t(0)));
}

namespace {

using namespace radius_lines;

// Section 3.5 with blocked rays ignored: one horizon sweep per line (see safety_radius.h),
// read past the map's edge only until every start has its first violation. That reach of cap + 1
// centerlines was 28% of the samples read at 1024^2; on the rock wall 1.7% of the lines need all
// of it (58% more than 8 centerlines), on the bricks, whose flat tops have large radii, 77%.
SafetyRadii compute_unblocked(const ReliefMap& map, const SafetyRadiusOptions& o, int cap) {
  return sweep_lines<float>(
      map, o, cap, 0.0, kNoSharedRounds,
      [&](const SweptLine& line, LineProfile<float>& profile, LineScratch<float>& scratch) {
        UnblockedLineSweep& sweep = scratch.unblocked;
        sweep.begin(o.step, o.error_allowed);
        long chunk = 8 * line.stride;  // 8 centerlines
        for (long count = line.end + 2;; count += chunk) {
          profile.read_to(count);
          if (sweep.read(profile.data(), int(profile.prefix()), int(line.end)) || profile.whole())
            break;
          chunk *= 2;
        }
        sweep.answers(scratch.first);
        narrow_by_answers(line, scratch.first.data(), sweep.samples_read(), cap);
      });
}

// Blocked rays counted, with no error allowed, where the texels a line's starts narrow are
// already small (on the rock wall at 1024^2, after the first directions most are 0): a start's
// answer can lower a texel only if it lies within that texel's radius, so each start is answered
// alone (first_conservative_violation_before), reading the profile only that far, and a start
// whose texels are all 0 not at all. The radii are the same as when every line is answered
// whole (SafetyRadius.StartsAnsweredAloneGiveTheSameRadii). A line goes this way when its
// starts would read at most kNearWork samples per sample of the line, as judged by the line
// before it in its direction (1/3 texel away: its texels much the same). On the rock wall at
// 1024^2, 4 was faster than 2, 8 and 16.
constexpr double kNearWork = 4;
// The radii are shared between the cores after each of the first rounds of directions while at
// least this share of the texels is at 0 (on the rock wall at 1024^2, 91% in the end; on the
// bricks 4%, so they share only the first).
constexpr double kShareWhileZeros = 0.25;

class NearStarts {
 public:
  NearStarts(double step, int cap) : step_(step), cap_(cap) {
    // An answer lowers a radius R only if (first - j) step <= R (radius_before).
    span_[0] = 0;
    for (int r = 1; r < 256; ++r) span_[r] = long(std::floor((r + 1e-9) / step)) + 1;
  }
  // The most samples a line's starts may read to go this way.
  static long work_limit(const SweptLine& line) { return long(kNearWork * double(line.length)); }
  bool wanted(const SweptLine& line, const LineScratch<double>& scratch) const {
    return scratch.near_work_last >= 0 && scratch.near_work_last <= work_limit(line);
  }
  // Samples a start reads at most when the largest radius among its texels is r (0 for r = 0).
  const long* span() const { return span_; }
  // Answers the starts of `line` one at a time and narrows their texels; returns the samples the
  // line after it would read so (narrow_by_answers' work) and counts the starts answered.
  long answer(const SweptLine line, LineProfile<double>& profile, long& answered) const {
    // Counted here, not in `answered`: a radius store may alias it, and the cores' scratch may
    // share a cache line.
    long work = 0, count = 0;
    for (long i = 0; i < line.starts(); ++i) {
      const uint8_t largest = line.largest(i);
      if (largest == 0) continue;
      ++count;
      const long j = line.start(i), end = std::min(line.length, j + span_[largest] + 1);
      // Most answers lie within a few samples: those read first, the rest only when needed.
      long first = end;
      for (long to = std::min(end, j + kFirstLook);; to = end) {
        profile.read_range(j, to);
        first = first_conservative_violation_before(profile.data(), int(j), int(to), step_);
        if (first < to || to == end) break;
      }
      const uint8_t narrowed =
          first < end ? line.narrow(i, uint8_t(radius_before(first, j, step_, cap_))) : largest;
      work += span_[narrowed];
    }
    answered += count;
    return work;
  }

 private:
  // Samples a start reads first (on the rock wall at 1024^2 half the answers lie within 9, three
  // quarters within 32).
  static constexpr long kFirstLook = 64;
  double step_;
  int cap_;
  long span_[256];
};

// Otherwise every start of a line at once in O(samples); with an error allowed, each start scans
// ahead up to the cap. A texel takes the radii of every line within a line spacing of it, so the
// two sampled lines that bracket any ray crossing it both bound its radius (on the one-texel
// walls of the robust tests, the crossing's own lines alone missed 19 of 2,048 grazing rays, the
// bracketing lines 8).
//
// A start's answer depends on the samples from it on alone. So the profile is read 64
// centerlines past the map's edge first, and only where some start has no violation there is
// the rest read and the line answered again from that start on. (On the rock wall at 1024^2,
// 64 was faster than 8, 24 and 128: a line answered twice costs more than the samples saved.)
//
// With `shortcuts` off, every line is answered whole and no radii are shared between rounds:
// what the shortcuts must equal.
SafetyRadii compute_conservative(const ReliefMap& map, const SafetyRadiusOptions& o, int cap,
                                 bool shortcuts) {
  const int limit = int(std::ceil((cap + 1) / o.step)) + 1;
  // Line answers for the starts from `from` (a start) on, over the samples read.
  auto answer_from = [&](const SweptLine& line, const LineProfile<double>& profile, long from,
                         LineScratch<double>& scratch) {
    const int n = int(profile.prefix());
    scratch.first.resize(size_t(n));
    if (o.error_allowed == 0) {
      std::vector<int>& tail = scratch.tail_first;
      first_conservative_violations(profile.data() + from, n - int(from), o.step, 0,
                                    int(line.stride), scratch.scratch, tail);
      for (long j = from; j <= line.end; j += line.stride)
        scratch.first[size_t(j)] = tail[size_t(j - from)] + int(from);
    } else {
      for (long j = from; j <= line.end; j += line.stride)
        scratch.first[size_t(j)] =
            first_two_hit_after(profile.data(), n, int(j), limit, o.step, o.error_allowed);
    }
  };
  const NearStarts near(o.step, cap);
  const bool near_allowed = shortcuts && o.error_allowed == 0 && !o.max_over_directions;
  const double share_while_zeros = near_allowed ? kShareWhileZeros : kNoSharedRounds;
  return sweep_lines<double>(
      map, o, cap, 1.0 / o.starts, share_while_zeros,
      [&](const SweptLine& line, LineProfile<double>& profile, LineScratch<double>& scratch) {
        if (near_allowed && near.wanted(line, scratch)) {
          scratch.near_work_last = near.answer(line, profile, scratch.starts_answered_alone);
          return;
        }
        // A line whose neighbour needed the rest likely does too (a brick's flat top): it is
        // read whole at once rather than answered twice.
        if (scratch.read_whole_last) profile.read_to(profile.length());
        profile.read_to(line.end + 1 + 64 * line.stride);  // 64 centerlines
        answer_from(line, profile, line.begin, scratch);
        long from = line.begin;
        while (from <= line.end && scratch.first[size_t(from)] < int(profile.prefix()))
          from += line.stride;
        scratch.read_whole_last = from <= line.end;
        if (from <= line.end && !profile.whole()) {
          profile.read_to(profile.length());
          answer_from(line, profile, from, scratch);
        }
        scratch.near_work_last =
            narrow_by_answers(line, scratch.first.data(), profile.prefix(), cap,
                              near_allowed ? near.span() : nullptr, NearStarts::work_limit(line));
      });
}

}  // namespace

int effective_max_radius(const ReliefMap& map, const SafetyRadiusOptions& o) {
  if (o.max_radius > 0) return std::min(o.max_radius, 255);
  return std::clamp(std::max(map.width, map.height), 1, 255);
}

namespace {

SafetyRadii timed_radii(const ReliefMap& map, const SafetyRadiusOptions& o, bool shortcuts) {
  const auto start = std::chrono::steady_clock::now();
  const int cap = effective_max_radius(map, o);
  SafetyRadii out = o.ignore_blocked ? compute_unblocked(map, o, cap)
                                     : compute_conservative(map, o, cap, shortcuts);
  out.compute_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace

SafetyRadii compute_safety_radii(const ReliefMap& map, const SafetyRadiusOptions& o) {
  return timed_radii(map, o, true);
}

SafetyRadii compute_safety_radii_without_shortcuts(const ReliefMap& map,
                                                   const SafetyRadiusOptions& o) {
  return timed_radii(map, o, false);
}

SafetyRadii cached_safety_radii(const ReliefMap& map, const SafetyRadiusOptions& o) {
  constexpr int kAlgorithmVersion = 4;  // bump when compute_safety_radii changes its answers
  char options[256];
  std::snprintf(options, sizeof options, "v%d|%d|%d|%.9g|%d|%.9g|%d|%d|", kAlgorithmVersion,
                o.directions, o.starts, o.step, effective_max_radius(map, o), o.error_allowed,
                int(o.ignore_blocked), int(o.max_over_directions));
  return cached_precompute("safety_radius", options, map.width, map.height, map.content_hash(),
                           &SafetyRadii::radius, [&] { return compute_safety_radii(map, o); });
}

}  // namespace rl
