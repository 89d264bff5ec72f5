#pragma once
// Writing result files so that a reader never sees half of one and a failed write never
// leaves anything under the final name: write to a temporary name unique to this process and
// call, check the write, then rename into place. Several runs may write into one output
// folder at once (their temporary names differ; the last rename wins, whole).
#include <cstdint>
#include <string>

namespace rl {

// A temporary name next to `path`, unique to this process and call, that keeps `path`'s
// extension last (image writers pick the format from it): "a/b.png" -> "a/b.png.tmp-PID-N.png".
std::string unique_temp_path(const std::string& path);

// Renames `tmp` to `path`; on failure removes `tmp` and throws std::runtime_error naming both.
void commit_temp(const std::string& tmp, const std::string& path);

// Writes `text` to `path` through a checked temporary file (the folder is created); throws
// std::runtime_error naming `path` and the system's reason when any step fails.
void write_text_atomic(const std::string& path, const std::string& text);

// The whole of a text file as written (binary: no line-ending translation); empty when it does
// not exist. Throws ConfigError naming `path` when it is not a regular file (a FIFO would block
// the reader) or holds more than `max_bytes`.
inline constexpr uintmax_t kReadTextLimit = uintmax_t(256) << 20;
std::string read_text(const std::string& path, uintmax_t max_bytes = kReadTextLimit);

}  // namespace rl
