// Disagreements over the pixels both cover: the shadow flag (over all of them, and with
// scene_shadows over those where both show the relief and those where both show an object), and
// what the pixel shows (a plain scene object, hit layer -1, against the relief: visibility
// resolved differently, as depth_correct decides it).
#include "metrics/metric.h"

#include <cmath>

namespace rl {
namespace {

// % of the jointly covered pixels that `counts(i)` keeps where `differs(i)`; `if_none` where
// there are none.
template <typename Counts, typename Differs>
double disagree_pct(const MetricInput& in, Counts&& counts, Differs&& differs,
                    double if_none = 0.0) {
  long both = 0, differ = 0;
  for (size_t i = 0; i < in.truth.size(); ++i)
    if (in.both_cover(i) && counts(i)) {
      ++both;
      differ += differs(i);
    }
  return both ? 100.0 * double(differ) / double(both) : if_none;
}

bool every_pixel(size_t) {
  return true;
}

bool shadows_differ(const MetricInput& in, size_t i) {
  return in.technique.shadowed(i) != in.truth.shadowed(i);
}

const MetricRegistrar shadow_agreement(
    {.name = "shadow agreement",
     .place = 50,
     .columns = {ColumnSpec{"shadow_disagree_pct", "% of covered_px",
                            "jointly covered pixels whose shadow flag differs from the truth's"}
                     .compared(0.25, 0)
                     .scored()},
     .measure = [](const MetricInput& in) -> std::vector<double> {
       return {disagree_pct(in, every_pixel, [&](size_t i) { return shadows_differ(in, i); })};
     }});

// Of the pixels where both show the relief (objects: false) or both show an object, the % whose
// shadow flags differ; NaN where there are none.
double shadow_disagree_pct_on(const MetricInput& in, bool objects) {
  return disagree_pct(
      in,
      [&](size_t i) {
        return shows_object(in.technique, i) == objects && shows_object(in.truth, i) == objects;
      },
      [&](size_t i) { return shadows_differ(in, i); }, std::nan(""));
}

const MetricRegistrar shadow_agreement_by_receiver(
    {.name = "shadow agreement by receiver",
     .place = 55,
     .columns = {ColumnSpec{"relief_shadow_disagree_pct", "% of pixels",
                            "scene_shadows: of the pixels where both show the relief, those whose "
                            "shadow flag differs from the truth's (what the relief receives)"}
                     .compared(0.25, 0),
                 ColumnSpec{"object_shadow_disagree_pct", "% of pixels",
                            "scene_shadows: of the pixels where both show a plain scene object, "
                            "those whose shadow flag differs from the truth's (what the objects "
                            "receive)"}
                     .compared(0.25, 0)},
     .applies = [](const MetricInput& in) { return in.scene_shadows; },
     .measure = [](const MetricInput& in) -> std::vector<double> {
       return {shadow_disagree_pct_on(in, false), shadow_disagree_pct_on(in, true)};
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
       return {disagree_pct(in, every_pixel, [&](size_t i) {
         return shows_object(in.technique, i) != shows_object(in.truth, i);
       })};
     }});

}  // namespace
}  // namespace rl
