// Claims evaluated against rows.csv, written into the README, verified (claims/claims.h).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "claims/claims.h"
#include "claims/tables_follow_rows.h"
#include "core/atomic_write.h"
#include "core/columns.h"
#include "core/error.h"
#include "output/outputs_record.h"
#include "output/report.h"
#include "output/rows_csv.h"

namespace rl {
namespace {

// Does `cell` say `wanted`? As numbers when both are, else as text.
bool cell_matches(const std::string& cell, const std::string& wanted) {
  if (const size_t bar = wanted.find('|'); bar != std::string::npos)
    return cell_matches(cell, wanted.substr(0, bar)) || cell_matches(cell, wanted.substr(bar + 1));
  double a, b;
  if (parse_number(cell, a) && parse_number(wanted, b)) return a == b;
  return cell == wanted;
}

double aggregate(const std::vector<double>& xs, const std::string& of) {
  if (of == "min") return *std::min_element(xs.begin(), xs.end());
  if (of == "max") return *std::max_element(xs.begin(), xs.end());
  double sum = 0;
  for (double x : xs) sum += x;
  return sum / double(xs.size());
}

std::vector<const CsvRow*> select(const std::vector<CsvRow>& rows, const std::string& where) {
  std::vector<std::pair<std::string, std::string>> terms;
  for (const std::string& term : claim_words(where)) {
    const size_t eq = term.find('=');
    terms.emplace_back(term.substr(0, eq), eq == std::string::npos ? "" : term.substr(eq + 1));
  }
  std::vector<const CsvRow*> out;
  for (const CsvRow& r : rows) {
    bool all = true;
    for (const auto& [field, value] : terms) {
      auto it = r.find(field);
      all = all && it != r.end() && cell_matches(it->second, value);
    }
    if (all) out.push_back(&r);
  }
  return out;
}

// Values of one claim, computed on demand; a value that cannot be read says why.
class ClaimValues {
 public:
  ClaimValues(const Claim& c, const std::vector<CsvRow>& rows) : claim_(c), rows_(rows) {}

  bool get(const std::string& name, double& out, std::string& why) {
    if (parse_number(name, out)) return true;
    if (auto it = done_.find(name); it != done_.end()) return out = it->second, true;
    if (depth_ > 16) return why = "values refer to each other in a cycle", false;
    auto v = std::find_if(claim_.values.begin(), claim_.values.end(),
                          [&](const ClaimValue& x) { return x.name == name; });
    if (v == claim_.values.end()) return why = "no value '" + name + "'", false;
    ++depth_;
    const bool ok = !v->match.empty()   ? per_row_ratio(*v, out, why)
                    : v->derive.empty() ? read(*v, out, why)
                                        : derive(*v, out, why);
    --depth_;
    if (ok) done_[name] = out;
    return ok;
  }

 private:
  bool read(const ClaimValue& v, double& out, std::string& why) {
    const std::vector<const CsvRow*> picked = select(rows_, v.where);
    std::vector<double> xs;
    for (const CsvRow* r : picked) {
      auto it = r->find(v.column);
      double x;
      if (it == r->end()) return why = "rows.csv has no column '" + v.column + "'", false;
      if (parse_number(it->second, x)) xs.push_back(x);
    }
    if (xs.empty())
      return why = "value '" + v.name + "': no row with a number in '" + v.column + "' where " +
                   v.where,
             false;
    if (v.of.empty() && picked.size() != 1)
      return why = "value '" + v.name + "': " + std::to_string(picked.size()) + " rows where " +
                   v.where + " (name an aggregate, or narrow the filter)",
             false;
    out = aggregate(xs, v.of);
    return true;
  }

  // Each numerator row paired with the denominator row that agrees on every `match` field.
  bool per_row_ratio(const ClaimValue& v, double& out, std::string& why) {
    const std::vector<const CsvRow*> num = select(rows_, v.where + " " + v.args[0]);
    const std::vector<const CsvRow*> den = select(rows_, v.where + " " + v.args[1]);
    std::vector<double> ratios;
    if (!rows_.empty() && !rows_.front().count(v.column))
      return why = "rows.csv has no column '" + v.column + "'", false;
    for (const CsvRow* a : num) {
      const CsvRow* partner = nullptr;
      for (const CsvRow* b : den)
        if (std::all_of(v.match.begin(), v.match.end(), [&](const std::string& f) {
              return a->count(f) && b->count(f) && a->at(f) == b->at(f);
            }))
          partner = b;
      double x, y;
      if (!partner || !parse_number(a->at(v.column), x) || !parse_number(partner->at(v.column), y))
        return why = "value '" + v.name + "': a row where " + v.args[0] +
                     " has no partner with a number in '" + v.column + "' where " + v.args[1],
               false;
      ratios.push_back(x / y);
    }
    if (ratios.empty())
      return why = "value '" + v.name + "': no row where " + v.where + " " + v.args[0], false;
    out = aggregate(ratios, v.of);
    return true;
  }

  bool derive(const ClaimValue& v, double& out, std::string& why) {
    std::vector<double> xs(v.args.size());
    for (size_t i = 0; i < xs.size(); ++i)
      if (!get(v.args[i], xs[i], why)) return false;
    if (v.derive == "ratio")
      out = xs[0] / xs[1];
    else if (v.derive == "difference")
      out = xs[0] - xs[1];
    else if (v.derive == "min_of")
      out = *std::min_element(xs.begin(), xs.end());
    else
      out = *std::max_element(xs.begin(), xs.end());
    if (!std::isfinite(out)) return why = "value '" + v.name + "' is not finite", false;
    return true;
  }

  const Claim& claim_;
  const std::vector<CsvRow>& rows_;
  std::map<std::string, double> done_;
  int depth_ = 0;
};

// A value as a sentence shows it: `digits` significant digits, no exponent below 1e7.
std::string format_claim_number(double v, int digits) {
  char buf[64];
  if (std::abs(v) >= std::pow(10.0, digits) && std::abs(v) < 1e7)
    std::snprintf(buf, sizeof buf, "%.0f", v);
  else
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

bool compare(double a, const std::string& op, double b) {
  if (op == "<") return a < b;
  if (op == "<=") return a <= b;
  if (op == ">") return a > b;
  if (op == ">=") return a >= b;
  return a == b;
}

// The rows a claim's pictures are of, and their files as rows.csv names them.
void check_pictures(const Claim& c, const std::vector<CsvRow>& rows, ClaimResult& r) {
  if (c.pictures.empty()) {
    if (describes_pictures(c.text))
      r.failures.push_back(
          "the text speaks of pictures but names none: add 'pictures' (the rows "
          "whose render, truth and heat map it describes)");
    return;
  }
  const std::vector<const CsvRow*> picked = select(rows, c.pictures);
  if (picked.empty()) r.failures.push_back("pictures: no row where " + c.pictures);
  auto cell = [](const CsvRow& row, const char* column) {
    auto it = row.find(column);
    return it == row.end() ? std::string() : it->second;
  };
  for (const CsvRow* row : picked)
    r.pictures.push_back({cell(*row, "scene") + " " + cell(*row, "technique") + " " +
                              cell(*row, "elevation_deg") + "°",
                          cell(*row, "image_render"), cell(*row, "image_truth"),
                          cell(*row, "image_error")});
}

ClaimResult check_claim(const Claim& c, const std::vector<CsvRow>& rows) {
  ClaimResult r;
  r.id = c.id;
  ClaimValues values(c, rows);
  std::string why;
  r.failures = check_failures(c, rows);
  check_pictures(c, rows, r);
  r.sentence = c.text;
  for (size_t at = r.sentence.find('{'); at != std::string::npos; at = r.sentence.find('{', at)) {
    const size_t end = r.sentence.find('}', at);
    const std::string name = r.sentence.substr(at + 1, end - at - 1);
    double v = 0;
    std::string shown = "?";
    auto spec = std::find_if(c.values.begin(), c.values.end(),
                             [&](const ClaimValue& x) { return x.name == name; });
    if (values.get(name, v, why))
      shown = format_claim_number(v, spec == c.values.end() ? 3 : spec->digits);
    else
      r.failures.push_back(why);
    r.sentence.replace(at, end - at + 1, shown);
    at += shown.size();
  }
  return r;
}

}  // namespace

std::vector<std::string> check_failures(const Claim& c, const std::vector<CsvRow>& rows) {
  ClaimValues values(c, rows);
  std::vector<std::string> failures;
  std::string why;
  for (const std::string& check : c.checks) {
    const std::vector<std::string> w = claim_words(check);
    double x[3] = {0, 0, 0};
    bool ok = true;
    for (size_t i = 0; i < w.size(); i += 2) ok = ok && values.get(w[i], x[i / 2], why);
    if (!ok) {
      failures.push_back(why);
      continue;
    }
    const bool holds = w[1] == "between" ? x[0] >= x[1] && x[0] <= x[2] : compare(x[0], w[1], x[1]);
    if (!holds) {
      std::string measured;
      for (size_t i = 0; i < w.size(); i += 2)
        measured += (i ? ", " : "") + w[i] + " = " + format_claim_number(x[i / 2], 6);
      failures.push_back("check '" + check + "' does not hold: " + measured);
    }
  }
  return failures;
}

std::vector<ClaimResult> check_claims(const ClaimsFile& file, const std::vector<CsvRow>& rows) {
  std::vector<ClaimResult> out;
  for (const Claim& c : file.claims) out.push_back(check_claim(c, rows));
  return out;
}

namespace {

// "Pictures: ..." after a claim's sentence: links to the committed files, or the command.
std::string pictures_markdown(const Claim& c, const ClaimResult& r) {
  if (r.pictures.empty()) return "";
  if (!r.pictures_committed) return " Pictures: `" + c.pictures_command + "`.";
  std::string md = " Pictures:";
  for (size_t i = 0; i < r.pictures.size(); ++i) {
    const ClaimPicture& p = r.pictures[i];
    md += std::string(i ? ";" : "") + " " + p.label + " [render](" + p.render + ") · [truth](" +
          p.truth + ") · [heat map](" + p.error + ")";
  }
  return md + ".";
}

// " Paper items: a, b (in part: c)." with each linked to its paper's section of the ledger.
std::string items_markdown(const Claim& c) {
  auto links = [](const std::vector<std::string>& ids) {
    std::string out;
    for (const std::string& id : ids)
      out += std::string(out.empty() ? "" : ", ") + "[" + id + "](../LEDGER.md#" +
             id.substr(0, id.find('/')) + ")";
    return out;
  };
  if (c.items.empty() && c.partly.empty()) return "";
  std::string md =
      " Paper items: " + (c.items.empty() ? std::string("none in full") : links(c.items));
  if (!c.partly.empty()) md += " (in part: " + links(c.partly) + ")";
  return md + ".";
}

}  // namespace

std::string claims_markdown(const ClaimsFile& file, const std::vector<ClaimResult>& results,
                            const std::vector<RendererRows>& others) {
  std::string md = std::string(kClaimsBegin) + "\n";
  for (size_t i = 0; i < file.claims.size(); ++i) {
    const Claim& c = file.claims[i];
    md += std::to_string(i + 1) + ". **" + c.judges + "** — *" + c.verdict + "*. " +
          results[i].sentence + pictures_markdown(c, results[i]) + items_markdown(c) +
          renderer_markdown(c, others) + "\n";
  }
  return md + renderers_checked_markdown(others) + kClaimsEnd;
}

namespace {

// Each claim whose line in the README's section (one numbered line per claim, in order) is not
// what the rows give now, named with what the README says and what the rows say from the first
// difference on: a moved number is reported against its claim, not only against the file.
std::string differing_claims(const std::string& now, const std::string& generated,
                             const ClaimsFile& file) {
  auto lines = [](const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
      if (!line.empty() && std::isdigit(static_cast<unsigned char>(line[0]))) out.push_back(line);
    return out;
  };
  const std::vector<std::string> said = lines(now), given = lines(generated);
  // A stretch of a line around byte `at`, cut at UTF-8 character boundaries.
  auto from = [](const std::string& line, size_t at) {
    auto boundary = [&](size_t b) {
      while (b > 0 && b < line.size() && (static_cast<unsigned char>(line[b]) & 0xC0) == 0x80) --b;
      return std::min(b, line.size());
    };
    const size_t start = boundary(at > 40 ? at - 40 : 0), stop = boundary(start + 100);
    return "'..." + line.substr(start, stop - start) + "...'";
  };
  std::string out;
  for (size_t i = 0; i < file.claims.size() && i < given.size(); ++i) {
    const std::string old = i < said.size() ? said[i] : "";
    if (old == given[i]) continue;
    size_t at = 0;
    while (at < old.size() && at < given[i].size() && old[at] == given[i][at]) ++at;
    out += file.claims[i].where + ": claim " + file.claims[i].id + ": the README " +
           (old.empty() ? std::string("has no line for it") : "says " + from(old, at)) +
           ", the rows give " + from(given[i], at) + "\n";
  }
  return out;
}

// The README's generated section: checked, or rewritten with `write`. Returns the failures.
int verify_readme(const std::string& dir, const std::string& generated, const ClaimsFile& file,
                  bool write, std::string& report) {
  const std::string path = dir + "/README.md";
  std::string readme = read_text(path);
  const size_t begin = readme.find(kClaimsBegin), end = readme.find(kClaimsEnd);
  if (begin == std::string::npos || end == std::string::npos || end < begin) {
    report += path + ": no generated verdict section (the lines '" + kClaimsBegin + "' and '" +
              kClaimsEnd + "')\n";
    return 1;
  }
  // A second section would pass unread: one section, generated, is the README's verdict.
  if (readme.find(kClaimsBegin, begin + 1) != std::string::npos ||
      readme.find(kClaimsEnd, end + 1) != std::string::npos) {
    report += path + ": more than one generated verdict section (the lines '" + kClaimsBegin +
              "' and '" + kClaimsEnd + "'): keep one\n";
    return 1;
  }
  const std::string now = readme.substr(begin, end + std::string(kClaimsEnd).size() - begin);
  if (now == generated) return 0;
  if (!write) {
    report += path + ": the verdict section differs from what claims.toml and rows.csv give now " +
              "(relieflab verify --write " + dir + ")\n" + differing_claims(now, generated, file);
    return 1;
  }
  readme.replace(begin, now.size(), generated);
  write_text_atomic(path, readme);
  report += path + ": verdict section rewritten from claims.toml\n";
  return 0;
}

// The report's verdict panel (output/report.h), where the folder has a report.
int verify_report_panel(const std::string& dir, const nlohmann::json& verdicts, bool write,
                        std::string& report) {
  const std::string path = dir + "/report.html";
  if (!std::filesystem::exists(path)) return 0;
  std::string page = read_text(path);
  if (report_verdicts(page) == verdicts) return 0;
  if (!write || !set_report_verdicts(page, verdicts)) {
    report += path + ": the verdict panel differs from the claims (relieflab verify --write " +
              dir + "; a report from before the panel needs scripts/reproduce.sh)\n";
    return 1;
  }
  write_text_atomic(path, page);
  report += path + ": verdict panel rewritten from claims.toml\n";
  return 0;
}

// Whether every picture file of a claim is in the folder; a claim whose pictures are not must
// name the command that makes them.
void check_pictures_committed(const std::string& dir, const Claim& c, ClaimResult& r) {
  if (r.pictures.empty()) return;
  r.pictures_committed = true;
  for (const ClaimPicture& p : r.pictures)
    for (const std::string* f : {&p.render, &p.truth, &p.error})
      r.pictures_committed =
          r.pictures_committed && !f->empty() && std::filesystem::exists(dir + "/" + *f);
  if (!r.pictures_committed && c.pictures_command.empty())
    r.failures.push_back("its pictures (" + std::to_string(r.pictures.size()) + " row(s) where " +
                         c.pictures +
                         ") are not in the folder and it names "
                         "no 'pictures_command' that makes them");
}

nlohmann::json panel_pictures(const Claim& c, const ClaimResult& r) {
  nlohmann::json out = {{"command", r.pictures_committed ? "" : c.pictures_command},
                        {"rows", nlohmann::json::array()}};
  if (r.pictures_committed)
    for (const ClaimPicture& p : r.pictures)
      out["rows"].push_back(
          {{"label", p.label}, {"render", p.render}, {"truth", p.truth}, {"error", p.error}});
  return out;
}

}  // namespace

namespace {

// The rows a verdict is generated from must be the rows the run wrote (the folder's and every
// other renderer's): else --write would launder edited rows into the README while the tables
// and the report still show the run's numbers.
int verify_rows_as_written(const std::string& dir, std::string& report) {
  std::vector<std::string> folders = {dir};
  for (const RendererRows& r : other_renderer_rows(dir)) folders.push_back(dir + "/" + r.folder);
  int failures = 0;
  for (const std::string& folder : folders)
    for (const std::string& line : outputs_record_differences(folder)) {
      report += line + "\n";
      ++failures;
    }
  return failures;
}

}  // namespace

// Every number of rows.csv is one its column can take (a wrong_pct of -50 would pass a claim
// that the error is small): the check a run makes before reusing a stored row.
int verify_values_in_range(const std::string& dir, const std::vector<CsvRow>& rows,
                           std::string& report) {
  int failures = 0;
  for (size_t i = 0; i < rows.size(); ++i)
    for (const auto& [column, text] : rows[i]) {
      const DeclaredColumn* col = find_column(column);
      double v = 0;
      if (!col || col->spec.kind != ColumnKind::Number || !parse_number(text, v)) continue;
      if (const std::string why = value_outside_range(col->spec, v); !why.empty()) {
        report += dir + "/rows.csv: row " + std::to_string(i + 1) + ": '" + column + "' holds " +
                  text + ", a value its column cannot take: " + why + "\n";
        ++failures;
      }
    }
  return failures;
}

int verify_result_folder(const std::string& dir, bool write, std::string& report) {
  // Nothing is checked or rewritten from rows the run did not write.
  if (const int edited = verify_rows_as_written(dir, report)) return edited;
  const std::vector<CsvRow> rows = read_rows_csv(dir + "/rows.csv");
  if (const int outside = verify_values_in_range(dir, rows, report)) return outside;
  if (const int unfollowed = verify_tables_follow_rows(dir, report)) return unfollowed;
  const ClaimsFile file = load_claims(dir + "/claims.toml");
  std::vector<ClaimResult> results = check_claims(file, rows);
  for (size_t i = 0; i < results.size(); ++i)
    check_pictures_committed(dir, file.claims[i], results[i]);
  int failures = 0;
  nlohmann::json panel = nlohmann::json::array();
  for (size_t i = 0; i < results.size(); ++i) {
    for (const std::string& f : results[i].failures)
      report += file.claims[i].where + ": claim " + results[i].id + ": " + f + "\n";
    failures += int(results[i].failures.size());
    panel.push_back({{"judges", file.claims[i].judges},
                     {"verdict", file.claims[i].verdict},
                     {"sentence", results[i].sentence},
                     {"holds", results[i].holds()}});
    if (!file.claims[i].items.empty()) panel.back()["items"] = file.claims[i].items;
    if (!file.claims[i].partly.empty()) panel.back()["partly"] = file.claims[i].partly;
    if (!results[i].pictures.empty())
      panel.back()["pictures"] = panel_pictures(file.claims[i], results[i]);
  }
  const std::vector<RendererRows> others = other_renderer_rows(dir);
  failures += verify_other_renderers(file, others, report);
  failures += verify_readme(dir, claims_markdown(file, results, others), file, write, report);
  return failures + verify_report_panel(dir, panel, write, report);
}

}  // namespace rl
