// Disagreements over the pixels both cover: the self-shadow flag, and what the pixel shows
// (a plain scene object, hit layer -1, against the relief: visibility resolved differently,
// as depth_correct decides it).
#include "metrics/metric.h"

namespace rl {
namespace {

// % of the jointly covered pixels where `differs(i)`.
template <typename Differs>
double disagree_pct(const MetricInput& in, Differs&& differs) {
  long both = 0, differ = 0;
  for (size_t i = 0; i < in.truth.size(); ++i)
    if (in.both_cover(i)) {
      ++both;
      differ += differs(i);
    }
  return both ? 100.0 * double(differ) / double(both) : 0.0;
}

const MetricRegistrar shadow_agreement(
    {.name = "shadow agreement",
     .place = 50,
     .columns = {ColumnSpec{"shadow_disagree_pct", "% of covered_px",
                            "jointly covered pixels whose self-shadow flag differs from the "
                            "truth's"}
                     .compared(0.25, 0)
                     .scored()},
     .measure = [](const MetricInput& in) -> std::vector<double> {
       return {disagree_pct(
           in, [&](size_t i) { return in.technique.shadowed(i) != in.truth.shadowed(i); })};
     }});

const MetricRegistrar object_agreement(
    {.name = "object agreement",
     .place = 60,
     .columns = {ColumnSpec{"object_disagree_pct", "% of covered_px",
                            "jointly covered pixels where one shows a plain scene object and the "
                            "other the relief"}
                     .compared(0.25, 0)
                     .scored()},
     .measure = [](const MetricInput& in) -> std::vector<double> {
       return {disagree_pct(in, [&](size_t i) {
         return shows_object(in.technique, i) != shows_object(in.truth, i);
       })};
     }});

}  // namespace
}  // namespace rl
