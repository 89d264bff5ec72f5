#include "sweep/tables.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

namespace rl {

std::vector<std::string> csv_columns(const std::vector<Row>& rows,
                                     const std::vector<std::string>& leading) {
  std::vector<std::string> cols = leading;
  for (const Row& r : rows)
    for (auto it = r.begin(); it != r.end(); ++it)
      if (std::find(cols.begin(), cols.end(), it.key()) == cols.end()) cols.push_back(it.key());
  return cols;
}

std::string format_value(const nlohmann::ordered_json& v) {
  if (v.is_null()) return "–";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  const double d = v.get<double>();
  if (!std::isfinite(d)) return std::isnan(d) ? "nan" : (d > 0 ? "inf" : "-inf");
  if (d == std::floor(d) && std::abs(d) < 1e9) return std::to_string(static_cast<long long>(d));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", d);
  return buf;
}

std::string format_csv(const std::vector<Row>& rows, const std::vector<std::string>& columns) {
  auto quote = [](const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  std::string out;
  for (size_t i = 0; i < columns.size(); ++i) out += (i ? "," : "") + quote(columns[i]);
  out += "\n";
  for (const Row& r : rows) {
    for (size_t i = 0; i < columns.size(); ++i) {
      std::string cell;
      auto it = r.find(columns[i]);
      if (it != r.end() && !it->is_null()) {
        if (it->is_number_float()) {
          char buf[40];
          std::snprintf(buf, sizeof buf, "%.9g", it->get<double>());
          cell = buf;
        } else {
          cell = format_value(*it);
        }
      }
      out += (i ? "," : "") + quote(cell);
    }
    out += "\n";
  }
  return out;
}

std::string format_markdown_table(const std::vector<Row>& rows, const TableSpec& spec) {
  auto key_of = [](const Row& r, const std::vector<std::string>& fields) {
    std::vector<std::string> k;
    for (const auto& f : fields) {
      auto it = r.find(f);
      k.push_back(it == r.end() ? "–" : format_value(*it));
    }
    return k;
  };
  std::vector<std::vector<std::string>> row_keys, col_keys;
  std::map<std::pair<std::vector<std::string>, std::vector<std::string>>, std::vector<const Row*>>
      cells;
  size_t collisions = 0, most_per_cell = 0;
  for (const Row& r : rows) {
    auto rk = key_of(r, spec.rows), ck = key_of(r, spec.columns);
    if (std::find(row_keys.begin(), row_keys.end(), rk) == row_keys.end()) row_keys.push_back(rk);
    if (std::find(col_keys.begin(), col_keys.end(), ck) == col_keys.end()) col_keys.push_back(ck);
    std::vector<const Row*>& cell = cells[{rk, ck}];
    cell.push_back(&r);
    if (cell.size() > 1) ++collisions;
    most_per_cell = std::max(most_per_cell, cell.size());
  }
  // A value of a cell: its one row's, or the mean or max over its rows' numbers.
  auto cell_text = [&](const std::vector<const Row*>& cell, const std::string& v) {
    if (spec.aggregate.empty() || cell.size() == 1) {
      auto f = cell.front()->find(v);
      return f == cell.front()->end() ? std::string("–") : format_value(*f);
    }
    double sum = 0, most = -std::numeric_limits<double>::infinity();
    int n = 0;
    for (const Row* r : cell) {
      auto f = r->find(v);
      if (f == r->end() || !f->is_number()) continue;
      const double x = f->get<double>();
      sum += x;
      most = std::max(most, x);
      ++n;
    }
    if (n == 0) return std::string("–");
    return format_value(nlohmann::ordered_json(spec.aggregate == "mean" ? sum / n : most));
  };
  std::string out;
  if (!spec.title.empty()) out += "### " + spec.title + "\n\n";
  // Header: row fields, then per column key each value.
  std::vector<std::string> header = spec.rows;
  for (const auto& ck : col_keys) {
    std::string group;
    for (size_t i = 0; i < ck.size(); ++i) group += (i ? " " : "") + spec.columns[i] + "=" + ck[i];
    for (const auto& v : spec.values) header.push_back(group.empty() ? v : group + "<br>" + v);
  }
  out += "|";
  for (const auto& h : header) out += " " + h + " |";
  out += "\n|";
  for (size_t i = 0; i < header.size(); ++i) out += i < spec.rows.size() ? " --- |" : " ---: |";
  out += "\n";
  for (const auto& rk : row_keys) {
    out += "|";
    for (const auto& k : rk) out += " " + k + " |";
    for (const auto& ck : col_keys) {
      auto it = cells.find({rk, ck});
      for (const auto& v : spec.values)
        out += " " + (it != cells.end() ? cell_text(it->second, v) : std::string()) + " |";
    }
    out += "\n";
  }
  if (collisions && spec.aggregate.empty())
    out += "\n> " + std::to_string(collisions) +
           " rows share a table cell with another row (the first is shown): add fields to "
           "'rows' or 'columns' to separate them.\n";
  else if (collisions)
    out += "\n> Each cell is the " + spec.aggregate + " over the rows that share it (up to " +
           std::to_string(most_per_cell) + " per cell).\n";
  return out;
}

}  // namespace rl
