#pragma once
// Error types. A ConfigError is the user's mistake (file, key, value named in the
// message); a GlError is a driver or shader problem; both stop before any row is written.
#include <stdexcept>
#include <string>

namespace rl {

struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct GlError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A library's error text as one line of sane length, for a message of ours (OpenImageIO's
// and Assimp's may hold newlines, and may be long).
inline std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text.size() > 200 ? text.substr(0, 200) + "..." : text;
}

}  // namespace rl
