#pragma once
// Writers for sweep results: rows.csv (one row per cell, every column) and Markdown tables
// laid out as the config declares (row fields, column fields, metric values). Every file is
// written to a temporary name and renamed, so a reader never sees half a table.
#include <optional>
#include <string>
#include <vector>

#include "config/config.h"
#include "core/atomic_write.h"
#include "output/row.h"

namespace rl {

// Column order: the given leading columns, then every other key in order of first appearance.
std::vector<std::string> csv_columns(const std::vector<Row>& rows,
                                     const std::vector<std::string>& leading);
std::string format_csv(const std::vector<Row>& rows, const std::vector<std::string>& columns);
// One CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text);
// A [[table]] laid out as its Markdown, LaTeX and HTML forms show it: one line per row key (in
// order of first appearance), per column key each value, combined by the table's aggregate
// where several rows share a table cell (then the footnote says so).
struct TableValueColumn {
  std::string group;   // the column key, "field=value ..." ("" when the table has no columns)
  std::string label;   // the column key in plain words (plain_column_label), unique per table
  std::string metric;  // the value's column in the rows
};
struct TableLine {
  std::vector<std::string> row_key;  // the row fields' values as the table shows them
  // Per value column: nullopt where no row has this line's row key and the column's column key;
  // a null json where those rows lack the metric.
  std::vector<std::optional<nlohmann::ordered_json>> values;
  std::vector<std::string> cell_keys;  // the keys of the rows behind the line's values
  // Per value column: an error column (measured_against_truth) with a truth_flagged row behind
  // it (its truth is not accurate enough at that view to score it: metrics/metrics.h); the
  // tables mark it and never bold it.
  std::vector<bool> flagged;
};
// The mark and note a table gives values resting on a truth_flagged row.
inline constexpr const char* kTruthFlagMark = "⚑";
std::string truth_flag_note();
struct TableLayout {
  std::string title;
  std::vector<std::string> row_fields;
  std::vector<TableValueColumn> value_columns;
  std::vector<TableLine> lines;
  std::string footnote;     // rows hidden or combined, "" when every table cell holds one row
  long flagged_values = 0;  // values resting on a truth_flagged row
};
TableLayout lay_out_table(const std::vector<Row>& rows, const TableSpec& spec);
// A column key as a person writes it: the technique bare, linear + binary steps as "32+6", a
// boolean parameter by its name ("exact distance" / "no exact distance"), an angle in degrees
// as "elevation 5°", other fields as
// "name value", unset settings ("-") left out: "relief 32+6" for technique=relief
// linear_steps=32 binary_steps=6. Tables show it with the full key on hover.
std::string plain_column_label(const std::vector<std::string>& fields,
                               const std::vector<std::string>& values);

std::string format_markdown_table(const std::vector<Row>& rows, const TableSpec& spec);
// The same table as a LaTeX booktabs tabular in a table float (the title as its caption), the
// best value of each value column in bold (format = "latex": what researchers paste into papers).
std::string format_latex_table(const std::vector<Row>& rows, const TableSpec& spec);
// A [[table]]'s file as a run writes it: its format's text, laid out from rows.csv's rows as
// rows_as_values reads them back (output/rows_csv.h), so that the table follows from rows.csv.
std::string format_table_file(const std::vector<Row>& rows_read_back, const TableSpec& spec);
// Is a lower value of `metric` better? `has_best` is false for columns with no better or worse
// (pixel counts, grid sizes, truth settings), which get no bold.
bool best_is_lowest(const std::string& metric, bool& has_best);
// A value as a table shows it: numbers to 4 significant digits, missing as "–".
std::string format_value(const nlohmann::ordered_json& v);

}  // namespace rl
