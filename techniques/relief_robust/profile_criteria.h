#pragma once
// The one-line criteria of the safety radii (Baboud & Decoret 2006, Section 3.5): on a height
// profile sampled along one ray direction, where does a start first stop being safe?
#include <vector>

namespace rl {

// The line criterion of ignore_blocked on one profile h[0..n) (heights, up = larger) sampled
// every `step` from where the line enters the map: first[j] = the first sample s2 > j at
// which a descending ray above h[j], unblocked over h[0..j], could have entered and left
// the surface (the horizon of s2 lies strictly after j), or n.
void first_unblocked_violations(const std::vector<float>& h, double step, double error_allowed,
                                std::vector<int>& first);

// The same criterion read a part of the profile at a time, so that a line is sampled only as
// far as its starts need: a sample's horizon depends on the samples before it alone, so the
// answers over a prefix that holds every start's first violation are the whole profile's.
class UnblockedLineSweep {
 public:
  // A new profile.
  void begin(double step, double error_allowed);
  // Takes in h[samples_read() .. h.size()) (h growing from call to call, its earlier samples
  // unchanged). True once some sample's horizon lies after last_start: every start up to it
  // then has its first violation among the samples read.
  bool read(const std::vector<float>& h, int last_start) {
    return read(h.data(), int(h.size()), last_start);
  }
  // The same where the profile's first n samples are h[0..n).
  bool read(const float* h, int n, int last_start);
  int samples_read() const { return read_; }
  // first[j], j < samples_read(): the first violation among the samples read, or their count.
  void answers(std::vector<int>& first) const;

 private:
  double step_ = 0, error_allowed_ = 0;
  std::vector<int> hull_, by_horizon_;
  int top_ = 0, read_ = 0, latest_horizon_ = -1;
};

// The first violation distance of one profile h[0..n) sampled every `step` (heights, up =
// larger), or +infinity: where a descending ray above h[0] could have entered and left.
double first_two_hit_distance(const std::vector<double>& h, double step, double error_allowed);

// The same criterion for a start at sample j, looking at most `limit` samples ahead: the index
// of the first violation, or h.size(). O(distance) per start.
int first_two_hit_after(const std::vector<double>& h, int j, int limit, double step,
                        double error_allowed);
// The same over the n heights from h.
int first_two_hit_after(const double* h, int n, int j, int limit, double step,
                        double error_allowed);

// first_two_hit_after(h, j, unlimited, step, 0) for the starts j = first_start, first_start +
// stride, ... at once, in O(n): first[j] is the first violation's index or n (unspecified at
// other samples). `scratch` is scratch space.
void first_conservative_violations(const std::vector<double>& h, double step, int first_start,
                                   int stride, std::vector<int>& scratch, std::vector<int>& first);
// The same over the n heights from h.
void first_conservative_violations(const double* h, int n, double step, int first_start, int stride,
                                   std::vector<int>& scratch, std::vector<int>& first);

// first_conservative_violations' answer for the one start j, looked for among the samples
// before `end` (j < end <= the heights read): its index, or `end` if it lies at or past it. In
// the same arithmetic, so the same answer wherever it lies before `end`; O(answer - j), for
// starts whose answer only matters when it is near.
int first_conservative_violation_before(const double* h, int j, int end, double step);

}  // namespace rl
