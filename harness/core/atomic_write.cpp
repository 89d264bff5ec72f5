#include "core/atomic_write.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

#include "core/error.h"

namespace rl {

std::string unique_temp_path(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const std::string ext = std::filesystem::path(path).extension().string();
  return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ext;
}

void commit_temp(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw std::runtime_error("cannot move " + tmp + " to " + path + ": " + ec.message());
  }
}

void write_text_atomic(const std::string& path, const std::string& text) {
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  const std::string tmp = unique_temp_path(path);
  // stdio, not iostreams: fclose reports a flush that failed (a full disk) as an error.
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const int write_errno = errno;
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed) {
    const int e = !written ? write_errno : errno;
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(e));
  }
  commit_temp(tmp, path);
}

std::string read_text(const std::string& path, uintmax_t max_bytes) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) return {};
  if (!std::filesystem::is_regular_file(status)) throw ConfigError(path + ": not a regular file");
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > max_bytes)
    throw ConfigError(path + ": " + std::to_string(size) + " bytes, more than the " +
                      std::to_string(max_bytes) + " this reads");
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace rl
