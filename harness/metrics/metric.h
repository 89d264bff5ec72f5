#pragma once
// A metric: a producer of row columns that compares a technique's G-buffer with the truth's.
// Each lives in a file of its own (metric_*.cpp) and registers itself at load:
//
//   const MetricRegistrar shadow_agreement({
//       .name = "shadow agreement", .place = 50,
//       .columns = {ColumnSpec{"shadow_disagree_pct", "% of covered_px", "..."}.scored()},
//       .measure = [](const MetricInput& in) { return std::vector<double>{...}; }});
//
// Its columns are declared as every producer's are (core/columns.h: unit, which way is better,
// the compare tolerance, a place in the report), so tables, `compare`, Pareto fronts and the
// report take them the day the file is added. compare_gbuffers (metrics/metrics.h) runs every
// metric that applies, in the order of `place`, which is also its columns' order in rows.csv.
// Adding a metric is one file and its test.
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "core/columns.h"
#include "core/gbuffer.h"

namespace rl {

// What a metric measures: the two G-buffers of one view and the lengths that give its errors
// their units.
struct MetricInput {
  const GBuffer& technique;
  const GBuffer& truth;
  double depth_world = 1;          // world length of the relief's depth: the unit of pos_err_*
  double texel_world = 1;          // world width of one texel at this view: the unit of *_texels
  bool ambient_occlusion = false;  // the scene asked for ambient occlusion
  bool scene_shadows = false;      // the scene asked for shadows among all its surfaces
  const GBuffer* footprint = nullptr;  // the truth's colour over pixel footprints, if asked for

  bool both_cover(size_t i) const { return technique.covered(i) && truth.covered(i); }
  bool either_covers(size_t i) const { return technique.covered(i) || truth.covered(i); }
  // World distance between the two hits of pixel i; a non-finite one counts as far away.
  double hit_distance(size_t i) const;
};

struct Metric {
  std::string name;  // what it measures, for messages ("coverage")
  // Where its columns sit in a row: metrics run, and write, in increasing place.
  double place = 0;
  std::vector<ColumnSpec> columns;
  // Whether this view asks for it (the AO columns only where the scene asks for AO); empty:
  // always.
  std::function<bool(const MetricInput&)> applies{};
  // One value per declared column, in their order. A column marked scored() is written empty
  // (NaN) by compare_gbuffers when neither side covers a pixel, whatever it returns.
  std::function<std::vector<double>(const MetricInput&)> measure;
};

// Every registered metric, in place order.
const std::vector<Metric>& registered_metrics();

// Registers `metric` and declares its columns (producer "metrics"). Throws std::logic_error
// when it has no name, no columns or no measure, or a metric of its name or place exists.
void register_metric(Metric metric);
// Unregisters (tests that register throwaway metrics clean up after themselves; the columns
// stay declared).
void unregister_metric(const std::string& name);

// Registers at load; a refusal is a bug in the metric's file: it prints and exits(3), as a
// technique's does.
struct MetricRegistrar {
  explicit MetricRegistrar(Metric metric);
};

// A colour channel as an image file holds it: clamped to [0, 1], a non-finite value black.
inline float stored_channel(float v) {
  return std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
}

// A plain scene object's pixel (hit layer -1), not the relief's.
inline bool shows_object(const GBuffer& g, size_t i) {
  return g.hit[i].z < -0.5f;
}

struct ErrorStats {
  double mean = 0, rmse = 0, p99 = 0, max = 0;
};

// mean / rmse / 99th percentile (nearest rank) / max of the values; zeros when empty.
ErrorStats error_stats(std::vector<double> values);

}  // namespace rl
