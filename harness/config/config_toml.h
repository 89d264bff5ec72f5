#pragma once
// Reading TOML values for the sweep config, with messages naming file, line and key
// ("file:line: what"). No file is opened here: paths are resolved, not read.
#include <set>
#include <string>
#include <vector>

#include <toml++/toml.h>
#include <glm/glm.hpp>

namespace rl {

// Context for messages: "file:line: what".
struct Src {
  std::string file;
  std::string at(const toml::node& n) const {
    return file + ":" + std::to_string(n.source().begin.line);
  }
};

[[noreturn]] void fail(const std::string& where, const std::string& what);
// The TOML of a regular file (claims, the papers' inventory), or ConfigError naming the file and
// the line of a syntax error.
toml::table parse_toml_file(const std::string& path);
// Fails on a key of `t` not in `allowed`, listing the known ones.
void check_keys(const toml::table& t, const std::set<std::string>& allowed, const Src& src,
                const std::string& section);
// A finite number (nan and inf are refused; so are true and false: `depth = true` is a slip,
// not 1).
double number(const toml::node& n, const Src& src, const std::string& key);
// The same, or true / false as 1 / 0: for flags and bool parameters, which also take 0 and 1.
double number_or_flag(const toml::node& n, const Src& src, const std::string& key);
// A number, or each of 3, in the closed range [lo, hi], named in the message when it is not.
double number_in(const toml::node& n, const Src& src, const std::string& key, double lo, double hi);
glm::dvec3 vec3_in(const toml::node& n, const Src& src, const std::string& key, double lo,
                   double hi);
// %g, for messages.
std::string format_number(double v);
std::string string_of(const toml::node& n, const Src& src, const std::string& key);
// true or false; anything else fails with "'key' must be true or false".
bool boolean_of(const toml::node& n, const Src& src, const std::string& key);
// A string that names files and folders: 1 to 64 of [A-Za-z0-9._-], not "." or "..", so it
// can never lead outside the output folder.
std::string plain_name(const toml::node& n, const Src& src, const std::string& key);
// A scalar or an array of scalars, as a list (with `flags`, true / false as 1 / 0).
std::vector<double> number_list(const toml::node& n, const Src& src, const std::string& key,
                                bool flags = false);
std::vector<std::string> string_list(const toml::node& n, const Src& src, const std::string& key);
glm::dvec3 vec3_of(const toml::node& n, const Src& src, const std::string& key);
int positive_int(const toml::node& n, const Src& src, const std::string& key, int lo, int hi);
// A file path from the config: absolute, or relative to `base_dir`, then to the repository
// root; fails when it does not exist.
std::string resolve_path(const std::string& p, const std::string& base_dir, const Src& src,
                         const toml::node& n);
// Is `name` a measured column of rows.csv (tables' values, plots' axes)? And all of them.
bool is_measured(const std::string& name);
std::string measured_list();

}  // namespace rl
