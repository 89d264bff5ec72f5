#pragma once
// The report a person reads: OUT/report.html and its assets folder (report_assets/: d3 from
// Debian's libjs-d3), opening from disk with no server and no network. Per [[table]] a
// sortable, filterable table laid out as its Markdown file (lay_out_table); per [[plot]] and
// group (scene, view) an error-against-cost plot with its Pareto front and a colour legend
// (hover: the setting and its numbers; click: the cell), groups with a single setting listed
// instead; per cell its render, truth and error heat map side by side with the heat map's
// scale and the cell's numbers (a picture missing beside the report is named); the run's
// config and run.log. d3 because Debian packages it as one browser bundle
// (Debian's Vega comes as 31 UMD modules that need d3 modules it does not ship), and a scatter
// with a front line is a few dozen lines of it; the SVG files of plots/ stay as static copies.
#include <string>
#include <vector>

#include "config/config.h"
#include "output/row.h"

namespace rl {

// The d3 bundle the report copies (RELIEFLAB_D3 overrides /usr/share/javascript/d3/d3.min.js).
std::string d3_script_path();

// Writes report.html and report_assets/ into out_dir for `rows` (the sweep's, as rows.csv).
// Without the d3 bundle the report is written without plots and says why; returns false then.
bool write_report(const SweepConfig& config, const std::vector<Row>& rows,
                  const std::vector<std::string>& parameter_columns, const std::string& out_dir);

// The report's verdict panel: a JSON array of {judges, verdict, sentence, holds} in its own
// script element, empty when a run writes the report; `relieflab verify --write` fills it from a
// result folder's claims (claims/claims.h). Replaces the panel's data in `page`; false when the
// page has no panel (a report written before it had one).
bool set_report_verdicts(std::string& page, const nlohmann::json& verdicts);
// The panel's data as it stands in `page` (null when there is none).
nlohmann::json report_verdicts(const std::string& page);

}  // namespace rl
