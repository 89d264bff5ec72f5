#pragma once
// Writers for sweep results: rows.csv (one row per cell, every column) and Markdown tables
// laid out as the config declares (row fields, column fields, metric values). Every file is
// written to a temporary name and renamed, so a reader never sees half a table.
#include <string>
#include <vector>

#include "core/atomic_write.h"
#include "sweep/config.h"
#include "sweep/row.h"

namespace rl {

// Column order: the given leading columns, then every other key in order of first appearance.
std::vector<std::string> csv_columns(const std::vector<Row>& rows,
                                     const std::vector<std::string>& leading);
std::string format_csv(const std::vector<Row>& rows, const std::vector<std::string>& columns);
std::string format_markdown_table(const std::vector<Row>& rows, const TableSpec& spec);
// The same table as a LaTeX booktabs tabular in a table float (the title as its caption), the
// best value of each value column in bold (format = "latex": what researchers paste into papers).
std::string format_latex_table(const std::vector<Row>& rows, const TableSpec& spec);
// Is a lower value of `metric` better? `has_best` is false for columns with no better or worse
// (pixel counts, grid sizes, truth settings), which get no bold.
bool best_is_lowest(const std::string& metric, bool& has_best);
// A value as a table shows it: numbers to 4 significant digits, missing as "–".
std::string format_value(const nlohmann::ordered_json& v);

}  // namespace rl
