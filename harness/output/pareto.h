#pragma once
// What accuracy costs: for each group of rows (e.g. one scene at one elevation), the points
// (cost, error) of every technique and setting, and their Pareto front, the settings that no
// other setting beats on both. Written as SVG plots and as a Markdown list of the fronts.
#include <string>
#include <vector>

#include "config/config.h"
#include "output/row.h"

namespace rl {

struct ParetoPoint {
  double x = 0, y = 0;
  std::string label;   // technique and parameters
  std::string series;  // technique (one colour each)
  std::string key;     // the row's cell key
  // Its row is truth_flagged and the plot's error is measured against the truth: drawn, but
  // not ranked (never on the front, never beating another point).
  bool flagged = false;
};

// One plot's rows: those with numeric x and y that share the values of spec.group.
struct PlotGroup {
  std::vector<std::string> values;  // of spec.group, as tables show them
  std::string title;                // "scene=..., elevation_deg=..."
  std::vector<ParetoPoint> points;  // labelled with technique and parameters
};

// The groups of `rows` in order of first appearance (the SVG plots' and the report's).
std::vector<PlotGroup> plot_groups(const std::vector<Row>& rows, const PlotSpec& spec,
                                   const std::vector<std::string>& parameter_columns);

// Indices of the points on the Pareto front (minimising x and y), ordered by x. A point is on
// it when no other point is at least as good on both and strictly better on one; flagged
// points take no part.
std::vector<size_t> pareto_front(const std::vector<ParetoPoint>& points);

std::string format_svg_plot(const std::vector<ParetoPoint>& points, const std::string& title,
                            const std::string& x_name, const std::string& y_name, bool log_y);

// Writes <out>/plots/<y>_vs_<x>__<group>.svg per group and returns the Markdown of the fronts.
std::string write_pareto_plots(const std::vector<Row>& rows, const PlotSpec& spec,
                               const std::vector<std::string>& parameter_columns,
                               const std::string& out_dir);

}  // namespace rl
