#include "output/provenance.h"

#include <algorithm>
#include <sstream>

namespace rl {

std::string Provenance::text() const {
  std::string out;
  for (const auto& [name, digest] : parts) out += (out.empty() ? "" : " ") + name + "=" + digest;
  return out;
}

Provenance Provenance::parse(const std::string& text) {
  Provenance p;
  std::istringstream in(text);
  std::string word;
  while (in >> word) {
    const size_t eq = word.find('=');
    if (eq == std::string::npos || eq == 0) return {};
    p.parts.emplace_back(word.substr(0, eq), word.substr(eq + 1));
  }
  return p;
}

std::string Provenance::part(const std::string& name) const {
  for (const auto& [n, digest] : parts)
    if (n == name) return digest;
  return "";
}

std::vector<std::string> differing_parts(const Provenance& a, const Provenance& b) {
  std::vector<std::string> names;
  for (const Provenance* p : {&a, &b})
    for (const auto& [name, digest] : p->parts)
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  if (a.parts.empty() || b.parts.empty())
    return names.empty() ? std::vector<std::string>{"all"} : names;
  std::vector<std::string> differ;
  for (const std::string& name : names)
    if (a.part(name) != b.part(name)) differ.push_back(name);
  return differ;
}

}  // namespace rl
