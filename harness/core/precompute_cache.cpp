#include "core/precompute_cache.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "core/hash.h"

namespace rl {
namespace {

std::filesystem::path cache_dir() {
  if (const char* d = std::getenv("RELIEFLAB_CACHE_DIR")) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME")) return std::filesystem::path(d) / "relieflab";
  if (const char* d = std::getenv("HOME")) return std::filesystem::path(d) / ".cache" / "relieflab";
  return std::filesystem::temp_directory_path() / "relieflab-cache";
}

std::filesystem::path cache_path(const std::string& folder, const std::string& key) {
  return cache_dir() / folder / (key + ".bin");
}

}  // namespace

std::string precompute_cache_key(const std::string& options, uint64_t map_content_hash) {
  return hex64(fnv1a64(options.data(), options.size(), map_content_hash));
}

bool read_precompute_cache(const std::string& folder, const std::string& key, void* out,
                           size_t bytes) {
  std::ifstream in(cache_path(folder, key), std::ios::binary);
  if (!in) return false;
  in.read(static_cast<char*>(out), std::streamsize(bytes));
  return in.gcount() == std::streamsize(bytes) && in.peek() == EOF;
}

void write_precompute_cache(const std::string& folder, const std::string& key, const void* data,
                            size_t bytes) {
  const std::filesystem::path path = cache_path(folder, key);
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  if (ec) return;
  const std::filesystem::path tmp = path.string() + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(static_cast<const char*>(data), std::streamsize(bytes));
    if (!out) {
      out.close();
      std::filesystem::remove(tmp, ec);
      return;
    }
  }
  std::filesystem::rename(tmp, path, ec);
}

}  // namespace rl
