#include "metrics/metric.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace rl {
namespace {

std::vector<Metric>& registry() {
  static std::vector<Metric> metrics;  // on first use: files register in any order
  return metrics;
}

}  // namespace

double MetricInput::hit_distance(size_t i) const {
  const double d = glm::distance(glm::dvec3(technique.position[i]), glm::dvec3(truth.position[i]));
  return std::isfinite(d) ? d : 1e30;
}

const std::vector<Metric>& registered_metrics() {
  return registry();
}

void register_metric(Metric metric) {
  if (metric.name.empty() || metric.columns.empty() || !metric.measure)
    throw std::logic_error("a metric needs a name, columns and a measure ('" + metric.name + "')");
  for (const Metric& m : registry())
    if (m.name == metric.name || m.place == metric.place)
      throw std::logic_error("metric '" + metric.name + "' takes the " +
                             (m.name == metric.name ? "name" : "place") + " of metric '" + m.name +
                             "'");
  declare_columns("metrics", metric.columns, metric.place);
  auto at = std::find_if(registry().begin(), registry().end(),
                         [&](const Metric& m) { return m.place > metric.place; });
  registry().insert(at, std::move(metric));
}

void unregister_metric(const std::string& name) {
  std::erase_if(registry(), [&](const Metric& m) { return m.name == name; });
}

MetricRegistrar::MetricRegistrar(Metric metric) {
  try {
    register_metric(std::move(metric));
  } catch (const std::logic_error& e) {
    std::fprintf(stderr, "relieflab: %s\n", e.what());
    std::exit(3);
  }
}

ErrorStats error_stats(std::vector<double> v) {
  ErrorStats s;
  if (v.empty()) return s;
  double sum = 0, sq = 0;
  for (double e : v) {
    sum += e;
    sq += e * e;
    s.max = std::max(s.max, e);
  }
  s.mean = sum / v.size();
  s.rmse = std::sqrt(sq / v.size());
  const size_t rank = static_cast<size_t>(std::ceil(0.99 * v.size())) - 1;
  std::nth_element(v.begin(), v.begin() + rank, v.end());
  s.p99 = v[rank];
  return s;
}

}  // namespace rl
