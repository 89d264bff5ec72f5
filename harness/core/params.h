#pragma once
// Technique parameters: declared with defaults and valid ranges in a technique's info(),
// checked against the config before any work starts.
#include <map>
#include <string>
#include <vector>

namespace rl {

enum class ParamKind { Int, Float, Bool };

struct ParamSpec {
  std::string name;
  ParamKind kind = ParamKind::Float;
  double default_value = 0;
  double min_value = 0;
  double max_value = 0;
  std::string doc;
  // Its default draws exactly what the technique drew before the parameter existed (no define
  // compiled, no resource bound): a cell at the default leaves it out of its key, so stored runs
  // and committed reproductions keep theirs. For parameters added to a technique later.
  bool neutral_default = false;
  // The GLSL define it compiles into the technique's programs, where it is a shader constant:
  // the value itself (an int; a bool as 0 or 1; a float in parentheses), or, with
  // `define_when_set`, defined as 1 only where the value is not 0.
  std::string define = "";
  bool define_when_set = false;
};

// Parameter values by name; ints and bools are stored as exact doubles.
using ParamValues = std::map<std::string, double>;

std::string param_kind_name(ParamKind k);
// Throws ConfigError naming `where` when the value is out of range or of the wrong kind.
void check_param_value(const ParamSpec& spec, double value, const std::string& where);
// The defaults of every spec, overridden by `given` (which must only name declared params).
ParamValues resolve_params(const std::vector<ParamSpec>& specs, const ParamValues& given,
                           const std::string& where);
std::string format_param(const ParamSpec& spec, double value);

// `name`'s value in `values`, read as the type its declaration in `specs` gives it (int, bool
// or double). Throws std::logic_error naming `owner` and the parameter when `specs` does not
// declare it, declares it of another kind, or `values` lacks it: code reads what it declares,
// as declared, so a renamed or retyped parameter fails where it is read, not in a picture.
template <typename T>
T typed_param(const std::vector<ParamSpec>& specs, const ParamValues& values,
              const std::string& name, const std::string& owner);
extern template int typed_param<int>(const std::vector<ParamSpec>&, const ParamValues&,
                                     const std::string&, const std::string&);
extern template bool typed_param<bool>(const std::vector<ParamSpec>&, const ParamValues&,
                                       const std::string&, const std::string&);
extern template double typed_param<double>(const std::vector<ParamSpec>&, const ParamValues&,
                                           const std::string&, const std::string&);
// The defines the declared parameters set (ParamSpec::define) at these values, by define name.
std::map<std::string, std::string> param_defines(const std::vector<ParamSpec>& specs,
                                                 const ParamValues& values);

}  // namespace rl
