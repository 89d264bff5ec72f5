#include "core/columns.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace rl {
namespace {

std::vector<DeclaredColumn>& catalog() {
  static std::vector<DeclaredColumn> columns;  // on first use: declarations run in any order
  return columns;
}

}  // namespace

void declare_columns(const std::string& producer, const std::vector<ColumnSpec>& columns,
                     double place) {
  // Libraries load in link order and files within one in any order: a producer's columns keep
  // their declared places whichever file declared first.
  auto at = std::find_if(catalog().begin(), catalog().end(), [&](const DeclaredColumn& c) {
    return c.producer == producer && c.place > place;
  });
  for (const ColumnSpec& c : columns) {
    if (c.name.empty() || c.meaning.empty())
      throw std::logic_error(producer + " declares a column without a name or a meaning");
    if (const DeclaredColumn* other = find_column(c.name)) {
      if (other->spec.unit != c.unit || other->spec.kind != c.kind)
        throw std::logic_error("column '" + c.name + "' is declared by " + other->producer +
                               " in '" + other->spec.unit + "' and by " + producer + " in '" +
                               c.unit + "'");
      continue;
    }
    at = std::next(catalog().insert(at, {c, producer, place}));
  }
}

const std::vector<DeclaredColumn>& declared_columns() {
  return catalog();
}

const DeclaredColumn* find_column(const std::string& name) {
  for (const DeclaredColumn& c : catalog())
    if (c.spec.name == name) return &c;
  return nullptr;
}

ValueRange column_range(const ColumnSpec& c) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const std::string& u = c.unit;
  // A share of a whole that contains what it counts is at most 100; of another population
  // (false hits of the truth's covered pixels) or a relative error, it may exceed it.
  for (const char* whole : {"% of union_px", "% of texels", "% of fragments", "% of pixels"})
    if (u == whole) return {0, 100};
  if (u.rfind("%", 0) == 0) return {0, inf};
  for (const char* unit : {"ms", "fetches", "ops / px", "texels", "pixels", "fragments", "bytes",
                           "1/s", "rays", "passes", "iterations", "cells", "triangles", "regions",
                           "maps", "frames", "faces", "crossings", "depth units"})
    if (u == unit) return {0, inf};
  if (u == "visibility") return {-1, 1};
  if (u == "degrees") return {-180, 180};
  if (u == "dB") return {-inf, 100};
  return {-inf, inf};
}

std::string value_outside_range(const ColumnSpec& c, double value) {
  const ValueRange r = column_range(c);
  if (std::isfinite(value) && value >= r.lo && value <= r.hi) return "";
  char text[160];
  std::snprintf(text, sizeof text, "%.6g lies outside [%g, %g]%s%s%s", value, r.lo, r.hi,
                c.unit.empty() ? "" : " (", c.unit.c_str(), c.unit.empty() ? "" : ")");
  return text;
}

std::vector<std::string> measured_columns() {
  std::vector<std::string> names;
  for (const DeclaredColumn& c : catalog())
    if (c.spec.kind == ColumnKind::Number || c.spec.kind == ColumnKind::Flag)
      names.push_back(c.spec.name);
  return names;
}

ColumnDeclaration::ColumnDeclaration(const std::string& producer,
                                     const std::vector<ColumnSpec>& columns) {
  try {
    declare_columns(producer, columns);
  } catch (const std::logic_error& e) {
    std::fprintf(stderr, "relieflab: %s\n", e.what());
    std::exit(3);
  }
}

}  // namespace rl
