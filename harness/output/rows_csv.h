#pragma once
// rows.csv read back (output/tables.h writes it): one map per row, column -> the cell's text, so
// a claim filters on exactly what the file says.
#include <map>
#include <string>
#include <vector>

#include "output/row.h"

namespace rl {

using CsvRow = std::map<std::string, std::string>;

// RFC 4180: commas, quoted cells with "" for a quote, newlines inside quotes. Throws
// ConfigError naming the file and line on a ragged row or an unclosed quote.
std::vector<CsvRow> read_rows_csv(const std::string& path);
// A cell (or a number in a claim) as a finite number: the whole text must parse.
bool parse_number(const std::string& text, double& out);
std::vector<CsvRow> parse_rows_csv(const std::string& text, const std::string& where);
// The rows again as values, each cell as format_csv wrote it: an integer, another number (nan and
// inf included), true or false, else text; an empty cell is no value. A run lays its tables out
// from these, so every table follows from rows.csv's bytes alone, and `relieflab verify` lays
// them out again to tell a table from rows that were edited under it.
std::vector<Row> rows_as_values(const std::vector<CsvRow>& rows);

}  // namespace rl
