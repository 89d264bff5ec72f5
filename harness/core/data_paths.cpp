#include "core/data_paths.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

namespace rl {

std::string library_dir() {
  Dl_info info{};
  if (!dladdr(reinterpret_cast<void*>(&library_dir), &info) || !info.dli_fname) return "";
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::canonical(info.dli_fname, ec);
  return ec ? "" : self.parent_path().string();
}

const std::string& data_root() {
  static const std::string root = [] {
    if (const char* env = std::getenv("RELIEFLAB_DATA_DIR"); env && *env) return std::string(env);
    const std::string lib = library_dir();
    std::error_code ec;
    if (!lib.empty()) {
      const std::filesystem::path installed =
          std::filesystem::path(lib).parent_path() / "share" / "relieflab";
      if (std::filesystem::is_directory(installed / "assets", ec)) return installed.string();
    }
    return std::string(RELIEFLAB_SOURCE_DIR);
  }();
  return root;
}

}  // namespace rl
