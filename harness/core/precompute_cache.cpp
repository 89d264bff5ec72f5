#include "core/precompute_cache.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/atomic_write.h"
#include "core/code_digest.h"
#include "core/hash.h"

namespace rl {
namespace {

constexpr char kMagic[8] = {'R', 'L', 'P', 'C', 'A', 'C', 'H', 'E'};

// The entry's identity: what the caller asked for and the code that computes it.
std::string with_code(const std::string& options, const std::source_location& where) {
  return options + " code=" + precompute_code_digest(where);
}

std::filesystem::path cache_path(const std::string& folder, const std::string& options,
                                 uint64_t map_hash) {
  return std::filesystem::path(precompute_cache_dir()) / folder /
         (hex64(fnv1a64(options.data(), options.size(), map_hash)) + ".bin");
}

template <typename T>
bool read_pod(std::ifstream& in, T& v) {
  in.read(reinterpret_cast<char*>(&v), sizeof v);
  return in.gcount() == std::streamsize(sizeof v);
}

template <typename T>
void write_pod(std::ofstream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof v);
}

}  // namespace

std::string precompute_cache_dir() {
  if (const char* d = std::getenv("RELIEFLAB_CACHE_DIR")) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"))
    return (std::filesystem::path(d) / "relieflab").string();
  if (const char* d = std::getenv("HOME"))
    return (std::filesystem::path(d) / ".cache" / "relieflab").string();
  return (std::filesystem::temp_directory_path() / "relieflab-cache").string();
}

bool read_precompute_cache(const std::string& folder, const std::string& asked, uint64_t map_hash,
                           void* out, size_t bytes, std::source_location where) {
  const std::string options = with_code(asked, where);
  // Anything but a regular file (a FIFO planted in the cache would block the run) is a miss.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(cache_path(folder, options, map_hash), ec)) return false;
  std::ifstream in(cache_path(folder, options, map_hash), std::ios::binary);
  if (!in) return false;
  char magic[8];
  in.read(magic, sizeof magic);
  if (in.gcount() != 8 || std::memcmp(magic, kMagic, 8) != 0) return false;
  uint64_t stored_hash = 0, payload = 0, checksum = 0;
  uint32_t options_size = 0;
  if (!read_pod(in, stored_hash) || stored_hash != map_hash) return false;
  if (!read_pod(in, options_size) || options_size != options.size()) return false;
  std::string stored_options(options_size, '\0');
  in.read(stored_options.data(), options_size);
  if (in.gcount() != std::streamsize(options_size) || stored_options != options) return false;
  if (!read_pod(in, payload) || payload != bytes || !read_pod(in, checksum)) return false;
  in.read(static_cast<char*>(out), std::streamsize(bytes));
  return in.gcount() == std::streamsize(bytes) && in.peek() == EOF &&
         fnv1a64(out, bytes) == checksum;
}

void write_precompute_cache(const std::string& folder, const std::string& asked, uint64_t map_hash,
                            const void* data, size_t bytes, std::source_location where) {
  const std::string options = with_code(asked, where);
  const std::filesystem::path path = cache_path(folder, options, map_hash);
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  if (ec) return;
  const std::filesystem::path tmp = unique_temp_path(path.string());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(kMagic, sizeof kMagic);
    write_pod(out, map_hash);
    write_pod(out, uint32_t(options.size()));
    out.write(options.data(), std::streamsize(options.size()));
    write_pod(out, uint64_t(bytes));
    write_pod(out, fnv1a64(data, bytes));
    out.write(static_cast<const char*>(data), std::streamsize(bytes));
    out.close();
    if (!out) {
      std::filesystem::remove(tmp, ec);
      return;
    }
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) std::filesystem::remove(tmp, ec);
}

}  // namespace rl
