#include "claims/ledger.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "claims/claims.h"
#include "config/config_toml.h"
#include "core/atomic_write.h"
#include "core/error.h"
#include "output/tables.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

PaperItem parse_item(const toml::node& n, const std::string& paper, const Src& src) {
  const toml::table* t = n.as_table();
  if (!t) fail(src.at(n), "each [[paper.item]] is a table");
  check_keys(*t, {"id", "what", "gap", "not_reproducible", "instead"}, src, "[[paper.item]]");
  for (const char* key : {"id", "what"})
    if (!t->get(key)) fail(src.at(n), std::string("[[paper.item]] needs '") + key + "'");
  PaperItem item;
  item.paper = paper;
  item.where = src.at(n);
  item.id = string_of(*t->get("id"), src, "id");
  item.what = string_of(*t->get("what"), src, "what");
  if (const toml::node* g = t->get("gap")) item.gap = string_of(*g, src, "gap");
  if (const toml::node* r = t->get("not_reproducible")) {
    item.not_reproducible = string_of(*r, src, "not_reproducible");
    if (!t->get("instead"))
      fail(src.at(n), "item '" + item.id +
                          "': 'not_reproducible' needs 'instead' (what is "
                          "compared in its place)");
  }
  if (const toml::node* i = t->get("instead")) item.instead = string_of(*i, src, "instead");
  return item;
}

// results/papers.toml: the papers and their items, in the order written.
void load_papers(const std::string& path, Ledger& ledger) {
  const Src src{path};
  const toml::table root = parse_toml_file(path);
  check_keys(root, {"paper"}, src, "the papers file");
  const toml::array* papers = root.get_as<toml::array>("paper");
  if (!papers) throw ConfigError(path + ": no [[paper]]");
  std::set<std::string> ids;
  for (const toml::node& n : *papers) {
    const toml::table* t = n.as_table();
    if (!t || !t->get("id") || !t->get("cite") || !t->get_as<toml::array>("item"))
      fail(src.at(n), "each [[paper]] has 'id', 'cite' and [[paper.item]]s");
    check_keys(*t, {"id", "cite", "item"}, src, "[[paper]]");
    const Ledger::Paper paper{string_of(*t->get("id"), src, "id"),
                              string_of(*t->get("cite"), src, "cite")};
    if (!ids.insert(paper.id).second) fail(src.at(n), "paper '" + paper.id + "' twice");
    ledger.papers.push_back(paper);
    for (const toml::node& item : *t->get_as<toml::array>("item")) {
      LedgerRow row;
      row.item = parse_item(item, paper.id, src);
      if (!ids.insert(paper.id + "/" + row.item.id).second)
        fail(src.at(item), "item '" + paper.id + "/" + row.item.id + "' twice");
      ledger.rows.push_back(row);
    }
  }
}

// Every claim's `items` and `partly`, onto the rows they name.
void attach_claims(const std::string& results_dir, Ledger& ledger) {
  std::map<std::string, LedgerRow*> by_id;
  for (LedgerRow& r : ledger.rows) by_id[r.item.paper + "/" + r.item.id] = &r;
  std::vector<fs::path> folders;
  for (const fs::directory_entry& e : fs::directory_iterator(results_dir))
    if (e.is_directory() && fs::is_regular_file(e.path() / "claims.toml"))
      folders.push_back(e.path());
  std::sort(folders.begin(), folders.end());
  for (const fs::path& folder : folders) {
    const ClaimsFile file = load_claims((folder / "claims.toml").string());
    for (const Claim& c : file.claims)
      for (const auto* list : {&c.items, &c.partly})
        for (const std::string& id : *list) {
          const auto it = by_id.find(id);
          if (it == by_id.end()) {
            ledger.problems.push_back(c.where + ": claim " + c.id + ": no item '" + id +
                                      "' in results/papers.toml");
            continue;
          }
          const bool full = list == &c.items;
          (full ? it->second->claims : it->second->partly_claims)
              .push_back(folder.filename().string() + "/" + c.id);
          (full ? it->second->verdicts : it->second->partly_verdicts).push_back(c.verdict);
        }
  }
}

// What the experiment found (ledger.h): from the verdicts of the claims that list the item in
// full, else of those that list it in part.
void find_outcome(LedgerRow& r) {
  if (r.status == "not_reproducible" || r.status == "missing") {
    r.outcome = r.status == "missing" ? "missing" : "not reproducible here";
    return;
  }
  const bool full = !r.claims.empty();
  const std::vector<std::string>& claims = full ? r.claims : r.partly_claims;
  const std::vector<std::string>& verdicts = full ? r.verdicts : r.partly_verdicts;
  bool confirmed = false, partly = false;
  for (size_t i = 0; i < verdicts.size(); ++i) {
    if (verdicts[i] == "not confirmed" || verdicts[i] == "refuted") {
      r.outcome = "contradicted";
      r.evidence = claims[i] + " (" + verdicts[i] + ")";
      return;
    }
    confirmed = confirmed || verdicts[i] == "confirmed";
    partly = partly || verdicts[i] == "partly confirmed";
  }
  if (!confirmed && !partly)
    r.outcome = "not judged";
  else
    r.outcome = full && !partly ? "confirmed" : "partly confirmed";
}

void judge(LedgerRow& r, std::vector<std::string>& problems) {
  const PaperItem& i = r.item;
  const std::string name = i.where + ": item " + i.paper + "/" + i.id;
  if (!i.not_reproducible.empty()) {
    r.status = "not_reproducible";
    if (!r.claims.empty())
      problems.push_back(name + ": cannot be reproduced here, yet " + r.claims.front() +
                         " lists it in full: list it under `partly` (what is compared instead)");
  } else if (!r.claims.empty()) {
    r.status = "reproduced";
    if (!i.gap.empty())
      problems.push_back(name + ": reproduced by " + r.claims.front() +
                         ", but still says what is missing ('gap'): drop it");
  } else {
    r.status = r.partly_claims.empty() ? "missing" : "partial";
    if (i.gap.empty())
      problems.push_back(name + ": " + r.status +
                         ", and says nothing of why ('gap'), or list it in a claim's `items`");
  }
}

std::string joined(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (const std::string& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

// The folders of "folder/claim" entries, once each, in order.
std::vector<std::string> folders_of(const LedgerRow& r) {
  std::vector<std::string> out;
  for (const auto* list : {&r.claims, &r.partly_claims})
    for (const std::string& c : *list) {
      const std::string folder = c.substr(0, c.find('/'));
      if (std::find(out.begin(), out.end(), folder) == out.end()) out.push_back(folder);
    }
  return out;
}

std::string note_of(const LedgerRow& r) {
  if (r.outcome == "contradicted")
    return "Contradicted by " + r.evidence + "." + (r.item.gap.empty() ? "" : " " + r.item.gap);
  if (r.status == "not_reproducible")
    return "Not here: " + r.item.not_reproducible + ". Compared instead: " + r.item.instead + ".";
  return r.item.gap;
}

std::string markdown_cell(const std::string& s) {
  std::string out;
  for (char c : s)
    out += c == '|' ? std::string("\\|") : c == '\n' ? std::string(" ") : std::string(1, c);
  return out;
}

struct Totals {
  std::map<std::string, int> by_status, by_outcome;
  int items = 0;
};

std::map<std::string, Totals> totals_by_paper(const Ledger& ledger) {
  std::map<std::string, Totals> t;
  for (const LedgerRow& r : ledger.rows) {
    for (const std::string& key : {r.item.paper, std::string()}) {
      ++t[key].items;
      ++t[key].by_status[r.status];
      ++t[key].by_outcome[r.outcome];
    }
  }
  return t;
}

}  // namespace

Ledger build_ledger(const std::string& results_dir) {
  Ledger ledger;
  load_papers(results_dir + "/papers.toml", ledger);
  attach_claims(results_dir, ledger);
  for (LedgerRow& r : ledger.rows) {
    judge(r, ledger.problems);
    find_outcome(r);
  }
  return ledger;
}

std::string ledger_csv(const Ledger& ledger) {
  std::string csv = "paper,item,status,outcome,folder,claims,partly_claims,what,note\n";
  for (const LedgerRow& r : ledger.rows)
    csv += r.item.paper + "," + r.item.id + "," + r.status + "," + csv_field(r.outcome) + "," +
           csv_field(joined(folders_of(r), ";")) + "," + csv_field(joined(r.claims, ";")) + "," +
           csv_field(joined(r.partly_claims, ";")) + "," + csv_field(r.item.what) + "," +
           csv_field(note_of(r)) + "\n";
  return csv;
}

std::string ledger_totals_markdown(const Ledger& ledger) {
  const std::map<std::string, Totals> totals = totals_by_paper(ledger);
  // Two tables: what is covered (status), and what was found (outcome).
  auto table = [&](const std::string& header, const auto& keys, auto Totals::*counts) {
    std::string md = header;
    auto line = [&](const std::string& name, const Totals& t) {
      md += "| " + name + " | " + std::to_string(t.items);
      for (const char* k : keys) {
        const auto it = (t.*counts).find(k);
        md += " | " + std::to_string(it == (t.*counts).end() ? 0 : it->second);
      }
      md += " |\n";
    };
    for (const Ledger::Paper& p : ledger.papers) line(p.id, totals.at(p.id));
    line("**all**", totals.at(""));
    return md;
  };
  return "Coverage: is there a reproduction of the item?\n\n" +
         table(
             "| paper | items | reproduced | partial | missing | not reproducible here |\n"
             "| --- | ---: | ---: | ---: | ---: | ---: |\n",
             kStatuses, &Totals::by_status) +
         "\nOutcome: what the reproduction found, from its claims' verdicts.\n\n" +
         table(
             "| paper | items | confirmed | partly confirmed | contradicted | not judged | "
             "missing | not reproducible here |\n"
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n",
             kOutcomes, &Totals::by_outcome);
}

std::string ledger_markdown(const Ledger& ledger) {
  std::string md =
      "# Coverage ledger: the five papers, item by item\n\n"
      "Generated by `relieflab ledger --write` from `results/papers.toml` (every table, figure, "
      "equation, algorithm and quantitative statement of the papers, kept by hand) and the "
      "claims of `results/*/claims.toml` that judge them (checked against their rows by "
      "`relieflab verify`). An item is *reproduced* when a claim lists it in full, *partial* "
      "when claims cover only part of it, *missing* when none does, *not reproducible* when it "
      "cannot be tested on these machines (what is compared instead is said). Its *outcome* is "
      "what the reproduction found, from the verdicts of those claims: *contradicted* when one "
      "is \"not confirmed\" or \"refuted\" (named in the note), *confirmed* when claims in "
      "full judge it and every judgement confirms it, *partly confirmed* when judged so or only "
      "in part, *not judged* when its claims only measure. Do not edit: `ledger.csv` holds the "
      "same rows.\n\n" +
      ledger_totals_markdown(ledger);
  for (const Ledger::Paper& p : ledger.papers) {
    md += "\n## " + p.id + "\n\n" + p.cite +
          "\n\n| item | what | status | outcome | claims | note |\n" +
          "| --- | --- | --- | --- | --- | --- |\n";
    for (const LedgerRow& r : ledger.rows) {
      if (r.item.paper != p.id) continue;
      std::string claims;
      for (const auto* list : {&r.claims, &r.partly_claims})
        for (const std::string& c : *list) {
          const std::string folder = c.substr(0, c.find('/')), id = c.substr(c.find('/') + 1);
          claims += std::string(claims.empty() ? "" : "; ") + "[" + folder + "](" + folder +
                    "/README.md) `" + id + "`" + (list == &r.partly_claims ? " (in part)" : "");
        }
      md += "| `" + r.item.id + "` | " + markdown_cell(r.item.what) + " | " + r.status + " | " +
            r.outcome + " | " + claims + " | " + markdown_cell(note_of(r)) + " |\n";
    }
  }
  return md;
}

namespace {

// Compares `path` with `text`, or writes it. Returns 1 on a stale file when only checking.
int publish(const std::string& path, const std::string& text, bool write, std::string& report) {
  const bool same = fs::is_regular_file(path) && read_text(path) == text;
  if (same) return 0;
  if (!write) {
    report += path +
              ": stale, not what results/papers.toml and the claims give now "
              "(relieflab ledger --write)\n";
    return 1;
  }
  write_text_atomic(path, text);
  report += path + ": written\n";
  return 0;
}

}  // namespace

int ledger_command(const std::string& results_dir, const std::string& readme, bool write,
                   std::string& report) {
  const Ledger ledger = build_ledger(results_dir);
  for (const std::string& p : ledger.problems) report += p + "\n";
  if (!ledger.problems.empty()) return int(ledger.problems.size());
  int failures = publish(results_dir + "/ledger.csv", ledger_csv(ledger), write, report);
  failures += publish(results_dir + "/LEDGER.md", ledger_markdown(ledger), write, report);
  std::string page = read_text(readme);
  const size_t begin = page.find(kLedgerBegin), end = page.find(kLedgerEnd);
  if (begin == std::string::npos || end == std::string::npos || end < begin) {
    report += readme + ": no ledger totals section (the lines '" + std::string(kLedgerBegin) +
              "' and '" + kLedgerEnd + "')\n";
    return failures + 1;
  }
  page.replace(begin, end - begin,
               std::string(kLedgerBegin) + "\n" + ledger_totals_markdown(ledger));
  return failures + publish(readme, page, write, report);
}

}  // namespace rl
