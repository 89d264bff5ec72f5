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

}  // namespace rl
