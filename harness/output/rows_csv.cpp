#include "output/rows_csv.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "core/atomic_write.h"
#include "core/columns.h"
#include "core/error.h"

namespace rl {
namespace {

// The next record's cells; false at the end of the text.
bool next_record(const std::string& text, size_t& at, int& line, std::vector<std::string>& cells,
                 const std::string& where) {
  cells.clear();
  if (at >= text.size()) return false;
  std::string cell;
  bool quoted = false;
  const int first_line = line;
  for (; at < text.size(); ++at) {
    const char c = text[at];
    if (quoted) {
      if (c == '"' && at + 1 < text.size() && text[at + 1] == '"') {
        cell += '"';
        ++at;
      } else if (c == '"') {
        quoted = false;
      } else {
        if (c == '\n') ++line;
        cell += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      cells.push_back(std::move(cell));
      cell.clear();
    } else if (c == '\n') {
      ++at;
      ++line;
      break;
    } else if (c != '\r') {
      cell += c;
    }
  }
  if (quoted)
    throw ConfigError(where + ":" + std::to_string(first_line) + ": unclosed quote in rows.csv");
  cells.push_back(std::move(cell));
  return true;
}

}  // namespace

bool parse_number(const std::string& text, double& out) {
  if (text.empty()) return false;
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(out);
}

std::vector<CsvRow> parse_rows_csv(const std::string& text, const std::string& where) {
  // A spreadsheet that saved the file may have put a UTF-8 byte-order mark before the header,
  // which would otherwise become part of the first column's name.
  size_t at = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
  int line = 1;
  std::vector<std::string> header, cells;
  if (!next_record(text, at, line, header, where))
    throw ConfigError(where + ": rows.csv is empty (no header)");
  for (size_t i = 0; i < header.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (header[i] == header[j])
        throw ConfigError(where + ":1: two columns are named '" + header[i] + "' (columns " +
                          std::to_string(j + 1) + " and " + std::to_string(i + 1) + ")");
  std::vector<CsvRow> rows;
  for (int record_line = line; next_record(text, at, line, cells, where); record_line = line) {
    if (cells.size() == 1 && cells[0].empty()) continue;  // a trailing newline
    if (cells.size() != header.size())
      throw ConfigError(where + ":" + std::to_string(record_line) + ": " +
                        std::to_string(cells.size()) + " cells, the header has " +
                        std::to_string(header.size()));
    CsvRow row;
    for (size_t i = 0; i < header.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(std::move(row));
  }
  return rows;
}

namespace {

// A declared column of text, or a naming identity (technique, scene: no unit), holds text even
// where it reads as a number (a key of sixteen digits).
bool holds_text(const std::string& column) {
  const DeclaredColumn* c = find_column(column);
  return c && (c->spec.kind == ColumnKind::Text ||
               (c->spec.kind == ColumnKind::Identity && c->spec.unit.empty()));
}

nlohmann::ordered_json cell_as_value(const std::string& column, const std::string& text) {
  if (holds_text(column)) return text;
  if (text == "true" || text == "false") return text == "true";
  if (text == "nan" || text == "inf" || text == "-inf")
    return text == "nan" ? std::nan("") : (text[0] == '-' ? -HUGE_VAL : HUGE_VAL);
  const bool integral = !text.empty() && text.size() < 19 &&
                        text.find_first_not_of("0123456789", text[0] == '-') == std::string::npos &&
                        text != "-";
  if (integral) return std::stoll(text);
  double v = 0;
  if (parse_number(text, v)) return v;
  return text;
}

}  // namespace

std::vector<Row> rows_as_values(const std::vector<CsvRow>& rows) {
  std::vector<Row> out;
  out.reserve(rows.size());
  for (const CsvRow& r : rows) {
    Row row = Row::object();
    for (const auto& [column, text] : r)
      if (!text.empty()) row[column] = cell_as_value(column, text);
    out.push_back(std::move(row));
  }
  return out;
}

std::vector<CsvRow> read_rows_csv(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw ConfigError(path + ": cannot read");
  return parse_rows_csv(read_text(path), path);
}

}  // namespace rl
