#include "core/atomic_write.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
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
  // Read with the system's own calls: a stream takes a read error (EIO, /proc/self/mem) for the
  // end of the file, and a config cut short there parses as another config.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw ConfigError(path + ": cannot open (" + std::strerror(errno) + ")");
  std::string text;
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      throw ConfigError(path + ": cannot read (" + std::strerror(err) + ")");
    }
    text.append(buf, size_t(n));
    if (text.size() > max_bytes) {
      ::close(fd);
      throw ConfigError(path + ": more than the " + std::to_string(max_bytes) +
                        " bytes this reads");
    }
  }
  ::close(fd);
  return text;
}

}  // namespace rl
