#include "gl/embedded_files.h"

#include <cstdio>
#include <cstdlib>

namespace rl {
namespace {

struct Registry {
  std::map<std::string, std::string> files;
  std::map<std::string, std::string> origin;  // path -> what registered it
};

Registry& registry() {
  static Registry r;  // constructed on first use: registrars run in any order
  return r;
}

}  // namespace

const std::map<std::string, std::string>& embedded_files() {
  return registry().files;
}

void register_embedded_files(const std::map<std::string, std::string>& files, const char* from) {
  Registry& r = registry();
  for (const auto& [path, text] : files) {
    const auto [it, added] = r.files.emplace(path, text);
    if (!added && it->second != text) {
      std::fprintf(stderr,
                   "relieflab: embedded file '%s' registered twice with different contents, by "
                   "%s and by %s\n",
                   path.c_str(), r.origin[path].c_str(), from);
      std::exit(3);
    }
    r.origin.emplace(path, from);
  }
}

}  // namespace rl
