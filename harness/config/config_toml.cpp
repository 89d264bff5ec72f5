#include "config/config_toml.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/columns.h"
#include "core/data_paths.h"
#include "core/error.h"

namespace rl {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw ConfigError(where + ": " + what);
}

toml::table parse_toml_file(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw ConfigError(path + ": cannot read");
  try {
    return toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw ConfigError(path + ":" + std::to_string(e.source().begin.line) +
                      ": TOML syntax error: " + std::string(e.description()));
  }
}

void check_keys(const toml::table& t, const std::set<std::string>& allowed, const Src& src,
                const std::string& section) {
  for (auto&& [k, v] : t) {
    if (!allowed.count(std::string(k.str()))) {
      std::string known;
      for (const auto& a : allowed) known += (known.empty() ? "" : ", ") + a;
      fail(src.at(v),
           "unknown key '" + std::string(k.str()) + "' in " + section + " (known: " + known + ")");
    }
  }
}

double number(const toml::node& n, const Src& src, const std::string& key) {
  if (auto v = n.value<double>(); v && (n.is_integer() || n.is_floating_point())) {
    // NaN and infinity are never meaningful here, and would hash alike into a cell key.
    if (!std::isfinite(*v))
      fail(src.at(n), "'" + key + "' must be a finite number, got " + format_number(*v));
    return *v;
  }
  if (n.is_boolean())
    fail(src.at(n), "'" + key + "' must be a number, got " +
                        (n.value<bool>().value() ? "true" : "false") +
                        " (true and false are for flags)");
  fail(src.at(n), "'" + key + "' must be a number");
}

double number_or_flag(const toml::node& n, const Src& src, const std::string& key) {
  if (n.is_boolean()) return n.value<bool>().value() ? 1.0 : 0.0;
  return number(n, src, key);
}

std::string format_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

double number_in(const toml::node& n, const Src& src, const std::string& key, double lo,
                 double hi) {
  const double v = number(n, src, key);
  if (!(v >= lo && v <= hi))
    fail(src.at(n), "'" + key + "' must be in [" + format_number(lo) + ", " + format_number(hi) +
                        "], got " + format_number(v));
  return v;
}

glm::dvec3 vec3_in(const toml::node& n, const Src& src, const std::string& key, double lo,
                   double hi) {
  const glm::dvec3 v = vec3_of(n, src, key);
  for (int i = 0; i < 3; ++i)
    if (!(v[i] >= lo && v[i] <= hi))
      fail(src.at(n), "each of '" + key + "' must be in [" + format_number(lo) + ", " +
                          format_number(hi) + "], got " + format_number(v[i]));
  return v;
}

std::string string_of(const toml::node& n, const Src& src, const std::string& key) {
  if (auto v = n.value<std::string>()) return *v;
  fail(src.at(n), "'" + key + "' must be a string");
}

std::string plain_name(const toml::node& n, const Src& src, const std::string& key) {
  const std::string v = string_of(n, src, key);
  const bool plain =
      !v.empty() && v.size() <= 64 && v != "." && v != ".." &&
      std::all_of(v.begin(), v.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
      });
  if (!plain) {
    const std::string shown =
        v.size() > 40 ? v.substr(0, 40) + "... (" + std::to_string(v.size()) + " characters)" : v;
    fail(src.at(n), "'" + key +
                        "' must be a plain name of 1 to 64 letters, digits, '_', '-' or "
                        "'.' (it names files and folders), got \"" +
                        shown + "\"");
  }
  return v;
}

// A scalar or an array of scalars, as a list of numbers.
std::vector<double> number_list(const toml::node& n, const Src& src, const std::string& key,
                                bool flags) {
  auto one = [&](const toml::node& e) {
    return flags ? number_or_flag(e, src, key) : number(e, src, key);
  };
  std::vector<double> out;
  if (const toml::array* a = n.as_array()) {
    if (a->empty()) fail(src.at(n), "'" + key + "' must not be empty");
    for (const toml::node& e : *a) out.push_back(one(e));
  } else {
    out.push_back(one(n));
  }
  return out;
}

std::vector<std::string> string_list(const toml::node& n, const Src& src, const std::string& key) {
  std::vector<std::string> out;
  if (const toml::array* a = n.as_array()) {
    for (const toml::node& e : *a) out.push_back(string_of(e, src, key));
  } else {
    out.push_back(string_of(n, src, key));
  }
  return out;
}

glm::dvec3 vec3_of(const toml::node& n, const Src& src, const std::string& key) {
  std::vector<double> v = number_list(n, src, key);
  if (v.size() != 3) fail(src.at(n), "'" + key + "' must be an array of 3 numbers");
  return {v[0], v[1], v[2]};
}

std::string resolve_path(const std::string& p, const std::string& base_dir, const Src& src,
                         const toml::node& n) {
  fs::path path(p);
  // A folder is never an asset (an empty path resolves to the config's own folder), nor is a
  // device, FIFO or socket: reading /dev/zero as an image or a mesh never ends.
  auto not_a_folder = [&](const fs::path& found) {
    if (p.empty() || fs::is_directory(found))
      fail(src.at(n), "'" + p + "' is a folder, not a file (" + found.string() + ")");
    if (!fs::is_regular_file(found))
      fail(src.at(n),
           "'" + p + "' is not a regular file (a device, FIFO or socket: " + found.string() + ")");
  };
  if (path.is_absolute()) {
    if (!fs::exists(path)) fail(src.at(n), "file not found: " + p);
    not_a_folder(path);
    return path.string();
  }
  for (const fs::path& dir : {fs::path(base_dir), fs::path(data_root())}) {
    fs::path candidate = dir / path;
    if (fs::exists(candidate)) {
      not_a_folder(candidate);
      return fs::weakly_canonical(candidate).string();
    }
  }
  fail(src.at(n), "file not found: " + p + " (looked in " + base_dir + " and " + data_root() + ")");
}

bool is_measured(const std::string& name) {
  const auto& m = measured_columns();
  return std::find(m.begin(), m.end(), name) != m.end();
}

std::string measured_list() {
  std::string out;
  for (const auto& m : measured_columns()) out += (out.empty() ? "" : ", ") + m;
  return out;
}

bool boolean_of(const toml::node& n, const Src& src, const std::string& key) {
  if (!n.is_boolean()) fail(src.at(n), "'" + key + "' must be true or false");
  return n.value<bool>().value();
}

int positive_int(const toml::node& n, const Src& src, const std::string& key, int lo, int hi) {
  double v = number(n, src, key);
  if (v != std::floor(v) || v < lo || v > hi)
    fail(src.at(n), "'" + key + "' must be an integer in [" + std::to_string(lo) + ", " +
                        std::to_string(hi) + "], got " + std::to_string(v));
  return int(v);
}

}  // namespace rl
