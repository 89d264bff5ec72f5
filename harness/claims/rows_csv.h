#pragma once
// rows.csv read back (output/tables.h writes it): one map per row, column -> the cell's text, so
// a claim filters on exactly what the file says.
#include <map>
#include <string>
#include <vector>

namespace rl {

using CsvRow = std::map<std::string, std::string>;

// RFC 4180: commas, quoted cells with "" for a quote, newlines inside quotes. Throws
// ConfigError naming the file and line on a ragged row or an unclosed quote.
std::vector<CsvRow> read_rows_csv(const std::string& path);
// A cell (or a number in a claim) as a finite number: the whole text must parse.
bool parse_number(const std::string& text, double& out);
std::vector<CsvRow> parse_rows_csv(const std::string& text, const std::string& where);

}  // namespace rl
