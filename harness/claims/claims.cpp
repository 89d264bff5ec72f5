#include "claims/claims.h"

#include <cmath>
#include <filesystem>
#include <regex>
#include <set>
#include <sstream>

#include "config/config_toml.h"
#include "core/error.h"

namespace rl {
namespace {

const std::set<std::string> kVerdicts = {"confirmed", "partly confirmed", "not confirmed",
                                         "refuted", "measured"};
const std::set<std::string> kOperators = {"<", "<=", ">", ">=", "=="};

// The {name}s of a sentence.
std::vector<std::string> placeholders(const std::string& text) {
  std::vector<std::string> names;
  for (size_t at = text.find('{'); at != std::string::npos; at = text.find('{', at + 1)) {
    const size_t end = text.find('}', at);
    if (end == std::string::npos) break;
    names.push_back(text.substr(at + 1, end - at - 1));
  }
  return names;
}

ClaimValue parse_value(const std::string& name, const toml::node& n, const Src& src) {
  const toml::table* t = n.as_table();
  if (!t) fail(src.at(n), "value '" + name + "' must be a table { where = ..., column = ... }");
  check_keys(*t,
             {"where", "column", "of", "ratio", "difference", "min_of", "max_of", "per_row_ratio",
              "match", "digits"},
             src, "value '" + name + "'");
  ClaimValue v;
  v.name = name;
  for (const char* derive : {"ratio", "difference", "min_of", "max_of"})
    if (const toml::node* d = t->get(derive)) {
      v.derive = derive;
      v.args = string_list(*d, src, derive);
      const bool pair = v.derive == "ratio" || v.derive == "difference";
      if (pair ? v.args.size() != 2 : v.args.empty())
        fail(src.at(*d),
             std::string("'") + derive + (pair ? "' names two values" : "' names values"));
    }
  if (const toml::node* p = t->get("per_row_ratio")) {
    v.args = string_list(*p, src, "per_row_ratio");
    if (v.args.size() != 2) fail(src.at(*p), "'per_row_ratio' names two filters");
    if (!t->get("match") || !t->get("column") || !t->get("of"))
      fail(src.at(n), "value '" + name + "': per_row_ratio needs 'match', 'column' and 'of'");
    v.match = string_list(*t->get("match"), src, "match");
    if (const toml::node* w = t->get("where")) v.where = string_of(*w, src, "where");
    v.column = string_of(*t->get("column"), src, "column");
    v.of = string_of(*t->get("of"), src, "of");
  } else if (v.derive.empty()) {
    if (!t->get("where") || !t->get("column"))
      fail(src.at(n),
           "value '" + name + "' needs 'where' and 'column' (or 'ratio' / 'difference')");
    v.where = string_of(*t->get("where"), src, "where");
    v.column = string_of(*t->get("column"), src, "column");
    if (const toml::node* of = t->get("of")) v.of = string_of(*of, src, "of");
  }
  if (!v.of.empty() && v.of != "mean" && v.of != "min" && v.of != "max")
    fail(src.at(*t->get("of")), "'of' must be \"mean\", \"min\" or \"max\"");
  if (const toml::node* d = t->get("digits")) v.digits = positive_int(*d, src, "digits", 1, 9);
  return v;
}

// Every name a claim uses is one of its values (or a number, in a check).
void check_names(const Claim& c, const toml::node& n, const Src& src) {
  std::set<std::string> known;
  for (const ClaimValue& v : c.values) known.insert(v.name);
  auto need = [&](const std::string& name, const std::string& where) {
    double number;
    if (!known.count(name) && !parse_number(name, number))
      fail(src.at(n), "claim '" + c.id + "': " + where + " names no value '" + name + "'");
  };
  for (const ClaimValue& v : c.values)
    if (v.match.empty())
      for (const std::string& arg : v.args) need(arg, "value '" + v.name + "'");
  for (const std::string& p : placeholders(c.text)) need(p, "the text");
  for (const std::string& check : c.checks) {
    const std::vector<std::string> w = claim_words(check);
    const bool compare = w.size() == 3 && kOperators.count(w[1]);
    const bool between = w.size() == 5 && w[1] == "between" && w[3] == "and";
    if (!compare && !between)
      fail(src.at(n), "claim '" + c.id + "': check '" + check +
                          "' is neither 'A op B' (op: < <= > >= ==) nor 'A between B and C'");
    for (size_t i = 0; i < w.size(); i += 2) need(w[i], "check '" + check + "'");
    // A check that holds whatever the rows say checks nothing: every side a number, or a value
    // compared with itself.
    bool any_value = false;
    for (size_t i = 0; i < w.size(); i += 2) any_value = any_value || known.count(w[i]);
    const bool self = w[0] == w[2] || (between && (w[0] == w[4]));
    if (!any_value || self)
      fail(src.at(n), "claim '" + c.id + "': check '" + check + "' holds whatever the rows say (" +
                          (self ? "a value compared with itself" : "it names no value") + ")");
  }
}

// not_on (the gpu-<name> folders whose rows the claim does not hold on) and not_on_why, which
// it needs: a verdict that holds on one renderer and not another says which, and why.
void parse_renderer_exceptions(const toml::table& t, const Src& src, Claim& c) {
  if (const toml::node* n = t.get("not_on")) {
    c.not_on = string_list(*n, src, "not_on");
    for (const std::string& folder : c.not_on)
      if (folder.rfind("gpu-", 0) != 0 || folder.find('/') != std::string::npos)
        fail(src.at(*n), "claim '" + c.id + "': not_on '" + folder +
                             "' is not a gpu-<name> folder beside rows.csv");
  }
  if (const toml::node* n = t.get("not_on_why")) c.not_on_why = string_of(*n, src, "not_on_why");
  if (c.not_on.empty() != c.not_on_why.empty())
    fail(src.at(t), "claim '" + c.id + "': 'not_on' and 'not_on_why' go together");
}

Claim parse_claim(const toml::node& n, const Src& src) {
  const toml::table* t = n.as_table();
  if (!t) fail(src.at(n), "each [[claim]] is a table");
  check_keys(*t,
             {"id", "judges", "verdict", "text", "values", "check", "pictures", "pictures_command",
              "items", "partly", "not_on", "not_on_why"},
             src, "[[claim]]");
  Claim c;
  c.where = src.at(n);
  for (const char* key : {"id", "judges", "verdict", "text"})
    if (!t->get(key)) fail(src.at(n), std::string("[[claim]] needs '") + key + "'");
  c.id = string_of(*t->get("id"), src, "id");
  c.judges = string_of(*t->get("judges"), src, "judges");
  c.verdict = string_of(*t->get("verdict"), src, "verdict");
  c.text = string_of(*t->get("text"), src, "text");
  if (const toml::node* p = t->get("pictures")) c.pictures = string_of(*p, src, "pictures");
  if (const toml::node* p = t->get("pictures_command")) {
    c.pictures_command = string_of(*p, src, "pictures_command");
    if (c.pictures.empty())
      fail(src.at(*p), "claim '" + c.id + "': 'pictures_command' makes the rows 'pictures' names");
  }
  for (const char* key : {"items", "partly"})
    if (const toml::node* list = t->get(key)) {
      std::vector<std::string>& ids = std::string(key) == "items" ? c.items : c.partly;
      ids = string_list(*list, src, key);
      for (const std::string& id : ids)
        if (id.find('/') == std::string::npos || id.front() == '/' || id.back() == '/')
          fail(src.at(*list), "claim '" + c.id + "': " + key + " '" + id +
                                  "' is not 'paper/item' (results/papers.toml names them)");
    }
  parse_renderer_exceptions(*t, src, c);
  if (!kVerdicts.count(c.verdict))
    fail(src.at(*t->get("verdict")), "claim '" + c.id + "': verdict '" + c.verdict +
                                         "' is not one of confirmed, partly confirmed, not "
                                         "confirmed, refuted, measured");
  if (const toml::table* values = t->get_as<toml::table>("values"))
    for (const auto& [name, v] : *values)
      c.values.push_back(parse_value(std::string(name), v, src));
  if (const toml::node* checks = t->get("check")) {
    const toml::array* a = checks->as_array();
    if (!a) fail(src.at(*checks), "checks are given as [[claim.check]] that = \"...\"");
    for (const toml::node& cn : *a) {
      const toml::table* ct = cn.as_table();
      if (!ct || !ct->get("that")) fail(src.at(cn), "[[claim.check]] needs 'that'");
      check_keys(*ct, {"that"}, src, "[[claim.check]]");
      c.checks.push_back(string_of(*ct->get("that"), src, "that"));
    }
  }
  if (c.checks.empty()) fail(src.at(n), "claim '" + c.id + "' has no [[claim.check]]");
  check_names(c, n, src);
  return c;
}

}  // namespace

bool describes_pictures(const std::string& text) {
  static const std::regex words(
      R"(heat ?maps?|pictures?|\brender(s|ed)?\b|\bimages?\b|\bfigures?\b(?!\s*\d)|\blooks?\b|\bglow)",
      std::regex::icase);
  return std::regex_search(text, words);
}

std::vector<std::string> claim_words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

ClaimsFile load_claims(const std::string& path) {
  const Src src{path};
  const toml::table root = parse_toml_file(path);
  check_keys(root, {"claim"}, src, "the claims file");
  ClaimsFile file;
  file.path = path;
  const toml::array* claims = root.get_as<toml::array>("claim");
  if (!claims) throw ConfigError(path + ": no [[claim]]");
  std::set<std::string> ids;
  for (const toml::node& n : *claims) {
    file.claims.push_back(parse_claim(n, src));
    if (!ids.insert(file.claims.back().id).second)
      fail(src.at(n), "claim id '" + file.claims.back().id + "' is used twice");
  }
  return file;
}

}  // namespace rl
