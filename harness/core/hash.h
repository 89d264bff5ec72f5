#pragma once
// Stable 64-bit FNV-1a hashing for result-store keys and caches: the same text gives
// the same key on every machine and run, so shards merge and sweeps resume.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

namespace rl {

// The default start is not FNV's published offset basis (14695981039346656037, a digit longer):
// a slip kept because every result-store key and cache name is derived from it. Digests meant
// for other tools pass the published one (output/outputs_record.cpp).
inline uint64_t fnv1a64(const void* data, size_t size, uint64_t h = 1469598103934665603ull) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;
  }
  return h;
}

inline uint64_t fnv1a64(const std::string& s) {
  return fnv1a64(s.data(), s.size());
}

// The content hash of a file (of nothing, when it cannot be read).
inline uint64_t file_content_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return fnv1a64(bytes);
}

inline std::string hex64(uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace rl
