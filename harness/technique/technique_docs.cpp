#include "technique/technique_docs.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace rl {
namespace {

const std::string kOpen = "<!-- generated: ";
const std::string kOpenTail = " (relieflab docs --update) -->";
const std::string kClose = "<!-- end generated -->";

// Table cells hold no raw '|' and no line break (either would end the cell or the table).
std::string cell(const std::string& s) {
  std::string out;
  for (char c : s)
    out += c == '|' ? std::string("\\|") : c == '\n' || c == '\r' ? " " : std::string(1, c);
  return out;
}

bool in_scope(const TechniqueEntry& e, DocsScope scope) {
  return scope == DocsScope::Registered || e.plugin.empty();
}

// Whether a column's producer is a technique outside `scope`.
bool column_in_scope(const DeclaredColumn& c, DocsScope scope) {
  const std::string prefix = "technique ";
  if (c.producer.rfind(prefix, 0) != 0) return true;
  const TechniqueEntry* e = TechniqueRegistry::instance().find(c.producer.substr(prefix.size()));
  return !e || in_scope(*e, scope);
}

std::string effects_cell(const EffectSet& effects) {
  std::string out;
  for (Effect e : effects.list()) out += (out.empty() ? "" : ", ") + ("`" + effect_name(e) + "`");
  return out.empty() ? "none" : out;
}

// What it promises (technique/contract.h), as the contract suite holds it to.
std::string contract_markdown(const TechniqueInfo& info) {
  const TechniqueContract& c = info.contract;
  auto finest = [&](const std::string& knob) -> std::string {
    for (const ParamSpec& p : info.params)
      if (p.name == knob && c.finest.count(knob))
        return ", finest " + format_param(p, c.finest.at(knob));
    return "";
  };
  std::string out =
      "Promise (held by `relieflab contract`, and by `ctest -L contract` in a build): " +
      answer_name(c.answer) + " answer; at most " + c.max_fetches_formula + " fetches per pixel";
  if (!c.knobs.empty()) {
    out += "; accuracy knobs: ";
    for (size_t i = 0; i < c.knobs.size(); ++i) {
      const AccuracyKnob& k = c.knobs[i];
      out += (i ? ", `" : "`") + k.param + "` (" + (k.larger_is_finer ? "larger" : "smaller") +
             " is finer" + finest(k.param) + ")";
    }
  }
  if (!c.accuracy.empty()) out += "; accuracy: " + c.accuracy;
  if (!c.hits_from_inside && c.ray_probe) out += "; its hit may lie above the surface";
  return out + ".\n\n";
}

const char* kind_name(ColumnKind k) {
  switch (k) {
    case ColumnKind::Number:
      return "number";
    case ColumnKind::Flag:
      return "flag";
    case ColumnKind::Text:
      return "text";
    case ColumnKind::Identity:
      return "identity";
  }
  return "?";
}

// Which way a number is better, and what `compare` allows it to move by default.
std::string better_name(const ColumnSpec& c) {
  if (c.kind != ColumnKind::Number || c.better == Better::Neither) return "-";
  std::string out = c.better == Better::Lower ? "lower" : "higher";
  char allowed[64];
  if (c.tolerance.watched()) {
    if (c.tolerance.rel > 0)
      std::snprintf(allowed, sizeof allowed, " (compare: %g%%)", 100 * c.tolerance.rel);
    else
      std::snprintf(allowed, sizeof allowed, " (compare: %g)", c.tolerance.abs);
    out += allowed;
  }
  return out;
}

}  // namespace

std::string columns_markdown(DocsScope scope) {
  // In the order a row reads (what names the cell, its errors, the truth's, the run's, the
  // representation's, the technique's), not the order the libraries happened to load in.
  auto rank = [](const std::string& producer) {
    const char* order[] = {"run (cell identity)", "metrics", "truth", "run", "relief", "technique"};
    for (int k = 0; k < 6; ++k)
      if (producer.rfind(order[k], 0) == 0) return k;
    return 6;
  };
  std::vector<DeclaredColumn> columns;
  for (const DeclaredColumn& c : declared_columns())
    if (column_in_scope(c, scope)) columns.push_back(c);
  std::stable_sort(columns.begin(), columns.end(),
                   [&](const DeclaredColumn& a, const DeclaredColumn& b) {
                     const int ra = rank(a.producer), rb = rank(b.producer);
                     return ra != rb ? ra < rb : (ra >= 4 && a.producer < b.producer);
                   });
  std::string out =
      "| column | unit | kind | better | meaning | declared by |\n"
      "| --- | --- | --- | --- | --- | --- |\n";
  for (const DeclaredColumn& c : columns)
    out += "| `" + c.spec.name + "` | " + cell(c.spec.unit) + " | " + kind_name(c.spec.kind) +
           (c.spec.scored_against_truth ? ", scored" : "") + " | " + better_name(c.spec) + " | " +
           cell(c.spec.meaning) + " | " + cell(c.producer) + " |\n";
  return out;
}

std::string techniques_markdown(DocsScope scope) {
  std::string out =
      "| technique | what | source | effects | reads | draws on |\n"
      "| --- | --- | --- | --- | --- | --- |\n";
  const auto& registry = TechniqueRegistry::instance();
  for (const std::string& name : registry.names()) {
    if (!in_scope(*registry.find(name), scope)) continue;
    const TechniqueInfo& info = registry.find(name)->info;
    out += "| [`" + name + "`](techniques/" + name + "/README.md) | " + cell(info.title) + " | " +
           cell(info.citation) + " | " + effects_cell(info.effects) + " | " +
           reads_in_words(info.draws) + " | " + draws_on_in_words(info.draws) + " |\n";
  }
  return out;
}

std::string interface_markdown(const TechniqueInfo& info) {
  std::string out = "Effects it can simulate: " + effects_cell(info.effects) +
                    ". Reads: " + reads_in_words(info.draws) +
                    ". Draws on: " + draws_on_in_words(info.draws) + ".\n\n";
  out += contract_markdown(info);
  for (size_t i = 0; i < info.columns.size(); ++i) {
    const ColumnSpec& c = info.columns[i];
    out += (i ? "; `" : "Columns it writes beside the harness's: `") + c.name + "` (" +
           (c.unit.empty() ? "" : c.unit + ": ") + c.meaning + ")" +
           (i + 1 == info.columns.size() ? ".\n\n" : "");
  }
  if (info.params.empty()) return out + "Parameters: none.\n";
  out += "| parameter | kind | default | range | meaning |\n| --- | --- | ---: | --- | --- |\n";
  for (const ParamSpec& p : info.params) {
    const std::string range =
        p.kind == ParamKind::Bool
            ? "true / false"
            : "[" + format_param(p, p.min_value) + ", " + format_param(p, p.max_value) + "]";
    out += "| `" + p.name + "` | " + param_kind_name(p.kind) + " | " +
           format_param(p, p.default_value) + " | " + range + " | " + cell(p.doc) + " |\n";
  }
  return out;
}

std::map<std::string, std::string> generated_blocks(DocsScope scope) {
  std::map<std::string, std::string> blocks = {{"techniques", techniques_markdown(scope)},
                                               {"columns", columns_markdown(scope)}};
  const auto& registry = TechniqueRegistry::instance();
  for (const std::string& name : registry.names())
    if (in_scope(*registry.find(name), scope))
      blocks["interface of " + name] = interface_markdown(registry.find(name)->info);
  return blocks;
}

std::vector<std::string> generated_block_keys(const std::string& text) {
  std::vector<std::string> keys;
  for (size_t at = text.find(kOpen); at != std::string::npos; at = text.find(kOpen, at + 1)) {
    const size_t key_end = text.find(kOpenTail, at);
    if (key_end == std::string::npos) break;
    keys.push_back(text.substr(at + kOpen.size(), key_end - at - kOpen.size()));
  }
  return keys;
}

std::string update_generated_blocks(const std::string& text,
                                    const std::map<std::string, std::string>& blocks) {
  std::string out;
  size_t pos = 0;
  while (true) {
    const size_t open = text.find(kOpen, pos);
    if (open == std::string::npos) break;
    const size_t key_end = text.find(kOpenTail, open);
    if (key_end == std::string::npos) break;
    const std::string key = text.substr(open + kOpen.size(), key_end - open - kOpen.size());
    const size_t body = key_end + kOpenTail.size() + 1;  // after the marker's newline
    const size_t close = text.find(kClose, body);
    if (close == std::string::npos)
      throw std::runtime_error("generated block '" + key + "' has no " + kClose);
    out += text.substr(pos, body - pos);
    auto it = blocks.find(key);
    out += it != blocks.end() ? it->second : text.substr(body, close - body);
    pos = close;
  }
  return out + text.substr(pos);
}

}  // namespace rl
