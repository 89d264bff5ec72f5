#include "core/data_paths.h"

#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "core/error.h"

namespace rl {

std::string library_dir() {
  Dl_info info{};
  if (!dladdr(reinterpret_cast<void*>(&library_dir), &info) || !info.dli_fname) return "";
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::canonical(info.dli_fname, ec);
  return ec ? "" : self.parent_path().string();
}

bool is_utf8(const std::string& text) {
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const size_t n = text.size();
  for (size_t i = 0; i < n;) {
    const unsigned c = s[i];
    int extra;
    unsigned min, cp;
    if (c < 0x80) {
      ++i;
      continue;
    } else if ((c & 0xE0) == 0xC0) {
      extra = 1, min = 0x80, cp = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      extra = 2, min = 0x800, cp = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      extra = 3, min = 0x10000, cp = c & 0x07;
    } else {
      return false;
    }
    for (int k = 1; k <= extra; ++k) {
      if (i + size_t(k) >= n || (s[i + size_t(k)] & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (s[i + size_t(k)] & 0x3F);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    i += size_t(extra) + 1;
  }
  return true;
}

void require_utf8_path(const std::string& path, const std::string& what) {
  if (is_utf8(path)) return;
  std::string shown;
  for (unsigned char c : path) {
    if (c >= 0x20 && c < 0x7F) {
      shown += char(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      shown += hex;
    }
  }
  throw ConfigError(what + " " + shown +
                    " is not valid UTF-8: ReliefLab records its paths in JSON; rename it");
}

const std::string& data_root() {
  static const std::string root = [] {
    if (const char* env = std::getenv("RELIEFLAB_DATA_DIR"); env && *env) return std::string(env);
    const std::string lib = library_dir();
    std::error_code ec;
    const std::filesystem::path installed =
        std::filesystem::path(lib).parent_path() / "share" / "relieflab";
    if (!lib.empty() && std::filesystem::is_directory(installed / "assets", ec))
      return installed.string();
    // The source tree only for the build tree's own libraries: an installed or relocated copy
    // whose share/ is missing must not read whatever lies at the build's paths on this machine.
    if (in_build_tree()) return std::string(RELIEFLAB_SOURCE_DIR);
    throw ConfigError(
        "ReliefLab's data (assets/ and configs/) is not where its libraries expect "
        "it: " +
        (installed / "assets").string() +
        " is missing (an incomplete install or package?); reinstall, or set "
        "RELIEFLAB_DATA_DIR to the folder holding assets/ and configs/");
  }();
  return root;
}

bool in_build_tree() {
  std::error_code ec;
  const std::filesystem::path built = std::filesystem::canonical(RELIEFLAB_BUILD_LIB_DIR, ec);
  const std::string lib = library_dir();
  return !ec && !lib.empty() && built == std::filesystem::path(lib);
}

}  // namespace rl
