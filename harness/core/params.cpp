#include "core/params.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/error.h"

namespace rl {

std::string param_kind_name(ParamKind k) {
  switch (k) {
    case ParamKind::Int:
      return "int";
    case ParamKind::Float:
      return "float";
    case ParamKind::Bool:
      return "bool";
  }
  return "?";
}

std::string format_param(const ParamSpec& spec, double value) {
  std::ostringstream s;
  if (spec.kind == ParamKind::Bool)
    s << (value != 0 ? "true" : "false");
  else if (spec.kind == ParamKind::Int)
    s << static_cast<long long>(value);
  else
    s << value;
  return s.str();
}

std::map<std::string, std::string> param_defines(const std::vector<ParamSpec>& specs,
                                                 const ParamValues& values) {
  std::map<std::string, std::string> defines;
  for (const ParamSpec& spec : specs) {
    if (spec.define.empty()) continue;
    const double v = values.at(spec.name);
    if (spec.define_when_set) {
      if (v != 0) defines[spec.define] = "1";
    } else if (spec.kind == ParamKind::Float) {
      defines[spec.define] = "(" + std::to_string(v) + ")";
    } else {
      defines[spec.define] = std::to_string(static_cast<long long>(v));
    }
  }
  return defines;
}

template <typename T>
T typed_param(const std::vector<ParamSpec>& specs, const ParamValues& values,
              const std::string& name, const std::string& owner) {
  constexpr ParamKind wanted = std::is_same_v<T, int>    ? ParamKind::Int
                               : std::is_same_v<T, bool> ? ParamKind::Bool
                                                         : ParamKind::Float;
  const ParamSpec* spec = nullptr;
  for (const ParamSpec& s : specs)
    if (s.name == name) spec = &s;
  if (!spec)
    throw std::logic_error(owner + " reads parameter '" + name + "', which it does not declare");
  if (spec->kind != wanted)
    throw std::logic_error(owner + " reads parameter '" + name + "' as " + param_kind_name(wanted) +
                           "; it is declared " + param_kind_name(spec->kind));
  const auto it = values.find(name);
  if (it == values.end())
    throw std::logic_error(owner + " reads parameter '" + name + "', which has no value");
  if constexpr (std::is_same_v<T, bool>)
    return it->second != 0;
  else
    return static_cast<T>(it->second);
}
template int typed_param<int>(const std::vector<ParamSpec>&, const ParamValues&, const std::string&,
                              const std::string&);
template bool typed_param<bool>(const std::vector<ParamSpec>&, const ParamValues&,
                                const std::string&, const std::string&);
template double typed_param<double>(const std::vector<ParamSpec>&, const ParamValues&,
                                    const std::string&, const std::string&);

void check_param_value(const ParamSpec& spec, double value, const std::string& where) {
  std::ostringstream err;
  if (!std::isfinite(value)) {
    err << where << ": parameter '" << spec.name << "' must be finite";
    throw ConfigError(err.str());
  }
  if (spec.kind == ParamKind::Int && value != std::floor(value)) {
    err << where << ": parameter '" << spec.name << "' must be an integer, got " << value;
    throw ConfigError(err.str());
  }
  if (spec.kind == ParamKind::Bool && value != 0 && value != 1) {
    err << where << ": parameter '" << spec.name << "' must be true or false";
    throw ConfigError(err.str());
  }
  if (spec.kind != ParamKind::Bool && (value < spec.min_value || value > spec.max_value)) {
    err << where << ": parameter '" << spec.name << "' = " << value << " is outside ["
        << spec.min_value << ", " << spec.max_value << "]";
    throw ConfigError(err.str());
  }
}

ParamValues resolve_params(const std::vector<ParamSpec>& specs, const ParamValues& given,
                           const std::string& where) {
  ParamValues out;
  for (const ParamSpec& s : specs) out[s.name] = s.default_value;
  for (const auto& [name, value] : given) {
    const ParamSpec* spec = nullptr;
    for (const ParamSpec& s : specs)
      if (s.name == name) spec = &s;
    if (!spec) {
      std::string known;
      for (const ParamSpec& s : specs) known += (known.empty() ? "" : ", ") + s.name;
      throw ConfigError(where + ": unknown parameter '" + name +
                        "' (known: " + (known.empty() ? "none" : known) + ")");
    }
    check_param_value(*spec, value, where);
    out[name] = value;
  }
  return out;
}

}  // namespace rl
