#include "output/tables.h"

#include "core/columns.h"
#include "metrics/metrics.h"
#include "technique/technique.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <set>

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

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string format_csv(const std::vector<Row>& rows, const std::vector<std::string>& columns) {
  std::string out;
  for (size_t i = 0; i < columns.size(); ++i) out += (i ? "," : "") + csv_field(columns[i]);
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
      out += (i ? "," : "") + csv_field(cell);
    }
    out += "\n";
  }
  return out;
}

namespace {

// The value of a table cell: its one row's, or the mean or max over its rows' numbers (null if
// none).
nlohmann::ordered_json cell_value(const std::vector<const Row*>& cell, const std::string& v,
                                  const std::string& aggregate) {
  if (aggregate.empty() || cell.size() == 1) {
    auto f = cell.front()->find(v);
    return f == cell.front()->end() ? nlohmann::ordered_json() : *f;
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
  if (n == 0) return nlohmann::ordered_json();
  return nlohmann::ordered_json(aggregate == "mean" ? sum / n : most);
}

std::string latex_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '_':
      case '%':
      case '&':
      case '#':
      case '$':
      case '{':
      case '}':
        out += '\\';
        out += c;
        break;
      case '~':
        out += "\\textasciitilde{}";
        break;
      case '^':
        out += "\\textasciicircum{}";
        break;
      case '\\':
        out += "\\textbackslash{}";
        break;
      default:
        out += c;
    }
  }
  // The table's "–" (no value) as LaTeX's en dash.
  for (size_t at; (at = out.find("–")) != std::string::npos;) out.replace(at, 3, "--");
  return out;
}

bool any_flagged(const std::vector<const Row*>& cell) {
  for (const Row* r : cell) {
    auto f = r->find("truth_flagged");
    if (f != r->end() && f->is_boolean() && f->get<bool>()) return true;
  }
  return false;
}

}  // namespace

std::string truth_flag_note() {
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "%s: the truth is not accurate enough at that view to score the row -- its "
                "bound exceeds %.2g texel on more than %.2g%% of the pixels "
                "(truth_uncertain_pct, truth_bound_texels).",
                kTruthFlagMark, kTruthBoundTarget, kTruthUncertainFlagPct);
  return buf;
}

TableLayout lay_out_table(const std::vector<Row>& rows, const TableSpec& spec) {
  auto key_of = [](const Row& r, const std::vector<std::string>& fields) {
    std::vector<std::string> k;
    for (const auto& f : fields) {
      auto it = r.find(f);
      k.push_back(it == r.end() ? "–" : format_value(*it));
    }
    return k;
  };
  // Row keys and column keys in order of first appearance; per (row key, column key) its rows.
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
  TableLayout t;
  t.title = spec.title;
  t.row_fields = spec.rows;
  std::set<std::string> labels;
  for (const auto& ck : col_keys) {
    std::string group;
    for (size_t i = 0; i < ck.size(); ++i) group += (i ? " " : "") + spec.columns[i] + "=" + ck[i];
    std::string label = plain_column_label(spec.columns, ck);
    if (!labels.insert(label).second) label = group;  // two keys read alike: keep the full one
    for (const auto& v : spec.values) t.value_columns.push_back({group, label, v});
  }
  for (const auto& rk : row_keys) {
    TableLine line;
    line.row_key = rk;
    for (const auto& ck : col_keys) {
      auto it = cells.find({rk, ck});
      for (const auto& v : spec.values) {
        if (it == cells.end()) {
          line.values.emplace_back(std::nullopt);
          line.flagged.push_back(false);
          continue;
        }
        line.values.emplace_back(cell_value(it->second, v, spec.aggregate));
        line.flagged.push_back(measured_against_truth(v) && any_flagged(it->second));
        t.flagged_values += line.flagged.back();
      }
      if (it != cells.end())
        for (const Row* r : it->second) line.cell_keys.push_back(r->value("key", std::string()));
    }
    t.lines.push_back(std::move(line));
  }
  if (collisions && spec.aggregate.empty())
    t.footnote = std::to_string(collisions) +
                 " rows share a table cell with another row (the first is shown): add fields to "
                 "'rows' or 'columns' to separate them.";
  else if (collisions)
    t.footnote = "Each cell is the " + spec.aggregate + " over the rows that share it (up to " +
                 std::to_string(most_per_cell) + " per cell).";
  return t;
}

namespace {

bool is_bool_parameter(const std::string& name) {
  const TechniqueRegistry& registry = TechniqueRegistry::instance();
  for (const std::string& t : registry.names())
    for (const ParamSpec& p : registry.find(t)->info.params)
      if (p.name == name) return p.kind == ParamKind::Bool;  // one kind per name (registry.h)
  return false;
}

std::string in_words(std::string name) {
  std::replace(name.begin(), name.end(), '_', ' ');
  return name;
}

}  // namespace

std::string plain_column_label(const std::vector<std::string>& fields,
                               const std::vector<std::string>& values) {
  std::map<std::string, std::string> set;
  for (size_t i = 0; i < fields.size() && i < values.size(); ++i)
    if (!values[i].empty() && values[i] != "-" && values[i] != "–") set[fields[i]] = values[i];
  std::vector<std::string> words;
  for (const std::string& f : fields) {
    auto it = set.find(f);
    if (it == set.end()) continue;
    const std::string& v = it->second;
    if (f == "technique") {
      words.push_back(v);
    } else if (f == "linear_steps" && set.count("binary_steps")) {
      words.push_back(v + "+" + set["binary_steps"]);
    } else if (f == "binary_steps" && set.count("linear_steps")) {
      continue;  // shown with the linear steps
    } else if (f.size() > 4 && f.compare(f.size() - 4, 4, "_deg") == 0) {
      words.push_back(in_words(f.substr(0, f.size() - 4)) + " " + v + "°");  // "elevation 5°"
    } else if (is_bool_parameter(f) && (v == "0" || v == "1")) {
      words.push_back((v == "1" ? "" : "no ") + in_words(f));
    } else {
      words.push_back(in_words(f) + " " + v);
    }
  }
  std::string label;
  for (const std::string& w : words) label += (label.empty() ? "" : " ") + w;
  return label;
}

bool best_is_lowest(const std::string& metric, bool& has_best) {
  // The column's declaration says which way it is better (core/columns.h); sizes, counts and
  // settings of the run have no best and get no bold.
  const DeclaredColumn* c = find_column(metric);
  const Better better = c ? c->spec.better : Better::Lower;
  has_best = better != Better::Neither;
  return better != Better::Higher;
}

std::string format_markdown_table(const std::vector<Row>& rows, const TableSpec& spec) {
  const TableLayout t = lay_out_table(rows, spec);
  std::string out;
  if (!t.title.empty()) out += "### " + t.title + "\n\n";
  std::vector<std::string> header = t.row_fields;
  for (const auto& c : t.value_columns)
    header.push_back(c.group.empty()
                         ? c.metric
                         : "<span title=\"" + c.group + "\">" + c.label + "</span><br>" + c.metric);
  out += "|";
  for (const auto& h : header) out += " " + h + " |";
  out += "\n|";
  for (size_t i = 0; i < header.size(); ++i) out += i < t.row_fields.size() ? " --- |" : " ---: |";
  out += "\n";
  for (const TableLine& line : t.lines) {
    out += "|";
    for (const auto& k : line.row_key) out += " " + k + " |";
    for (size_t c = 0; c < line.values.size(); ++c) {
      const auto& v = line.values[c];
      out += " " + (v ? format_value(*v) : std::string());
      if (line.flagged[c] && v && !v->is_null()) out += std::string(" ") + kTruthFlagMark;
      out += " |";
    }
    out += "\n";
  }
  if (!t.footnote.empty()) out += "\n> " + t.footnote + "\n";
  if (t.flagged_values) out += "\n> " + truth_flag_note() + "\n";
  return out;
}

std::string format_latex_table(const std::vector<Row>& rows, const TableSpec& spec) {
  const TableLayout t = lay_out_table(rows, spec);
  // Per value column the best number over the lines, for the bold.
  const size_t value_columns = t.value_columns.size();
  std::vector<double> best(value_columns, std::numeric_limits<double>::quiet_NaN());
  for (size_t c = 0; c < value_columns; ++c) {
    bool has_best = false;
    const bool lowest = best_is_lowest(t.value_columns[c].metric, has_best);
    if (!has_best) continue;
    for (const TableLine& line : t.lines) {
      const auto& x = line.values[c];
      if (!x || !x->is_number() || line.flagged[c]) continue;
      const double d = x->get<double>();
      if (!std::isfinite(d)) continue;
      if (std::isnan(best[c]) || (lowest ? d < best[c] : d > best[c])) best[c] = d;
    }
  }
  std::string out =
      "% Generated by relieflab from the sweep's rows; needs \\usepackage{booktabs}.\n";
  out += "\\begin{table}\n\\centering\n";
  if (!t.title.empty()) out += "\\caption{" + latex_escape(t.title) + "}\n";
  out += "\\begin{tabular}{" + std::string(t.row_fields.size(), 'l') +
         std::string(value_columns, 'r') + "}\n\\toprule\n";
  std::vector<std::string> header;
  for (const auto& r : t.row_fields) header.push_back(latex_escape(r));
  for (const auto& c : t.value_columns)
    header.push_back(latex_escape(c.group.empty() ? c.metric : c.label + " " + c.metric));
  for (size_t i = 0; i < header.size(); ++i) out += (i ? " & " : "") + header[i];
  out += " \\\\\n\\midrule\n";
  for (const TableLine& line : t.lines) {
    std::vector<std::string> cells;
    for (const auto& k : line.row_key) cells.push_back(latex_escape(k));
    for (size_t c = 0; c < value_columns; ++c) {
      const auto& x = line.values[c];
      if (!x) {
        cells.push_back("");
        continue;
      }
      std::string text = latex_escape(format_value(*x));
      if (x->is_number() && !line.flagged[c] && !std::isnan(best[c]) && x->get<double>() == best[c])
        text = "\\textbf{" + text + "}";
      if (line.flagged[c] && !x->is_null()) text += "$^\\dagger$";
      cells.push_back(text);
    }
    for (size_t i = 0; i < cells.size(); ++i) out += (i ? " & " : "") + cells[i];
    out += " \\\\\n";
  }
  out += "\\bottomrule\n\\end{tabular}\n";
  if (!t.footnote.empty())
    out += "\\par\\smallskip{\\footnotesize " + latex_escape(t.footnote) + "}\n";
  if (t.flagged_values) {
    std::string note = truth_flag_note();
    note.replace(0, std::string(kTruthFlagMark).size(), "");
    out += "\\par\\smallskip{\\footnotesize $^\\dagger$" + latex_escape(note) + "}\n";
  }
  out += "\\end{table}\n";
  return out;
}

std::string format_table_file(const std::vector<Row>& rows_read_back, const TableSpec& spec) {
  return spec.format == "latex" ? format_latex_table(rows_read_back, spec)
                                : format_markdown_table(rows_read_back, spec);
}

}  // namespace rl
