#include "core/columns.h"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace rl {
namespace {

std::vector<DeclaredColumn>& catalog() {
  static std::vector<DeclaredColumn> columns;  // on first use: declarations run in any order
  return columns;
}

}  // namespace

void declare_columns(const std::string& producer, const std::vector<ColumnSpec>& columns) {
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
    catalog().push_back({c, producer});
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
