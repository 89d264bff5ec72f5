#include "safety_radius.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include <unistd.h>

#include <glm/gtc/constants.hpp>

#include "core/hash.h"
#include "core/parallel.h"

namespace rl {

int SafetyRadii::zero_count() const {
  return int(std::count(radius.begin(), radius.end(), uint8_t(0)));
}

namespace {

// The scan of first_two_hit_distance over heights produced on demand by height(k), stopping
// at sample `limit`: the radius search only needs violations nearer than its current radius.
template <typename Height>
double scan_profile(Height&& height, int limit, double step, double error_allowed) {
  // A descending ray (height falling at any rate k >= 0) that is above the surface at 0 dips
  // below it at s1 and is above again at s2 > s1 exactly when, for the lowest such ray:
  // - h(s2) <= h(0): the chord from (0, h0) to (s2, h(s2)) passes below some h(s1), i.e. the
  //   largest slope from the start to an earlier point exceeds the slope to s2;
  // - h(s2) > h(0): a horizontal ray just above h(s2) passes below an earlier, higher h(s1).
  // A dip of at most error_allowed does not count (Figure 12's trade of error for speed).
  const double inf = std::numeric_limits<double>::infinity();
  const double h0 = height(0);
  double max_slope = -inf, max_h = -inf;
  for (int k = 1; k < limit; ++k) {
    const double s = k * step, hk = height(k);
    const double slope = (hk - h0) / s;
    if (hk <= h0) {
      if (max_slope > slope + 1e-12) return s;
    } else if (max_h > hk + 1e-12) {
      return s;
    }
    max_slope = std::max(max_slope, (hk - error_allowed - h0) / s);
    max_h = std::max(max_h, hk - error_allowed);
  }
  return inf;
}

}  // namespace

double first_two_hit_distance(const std::vector<double>& h, double step, double error_allowed) {
  return scan_profile([&](int k) { return h[size_t(k)]; }, int(h.size()), step, error_allowed);
}

namespace {

// Bilinear depth at texel-centre coordinates (x, y), wrapping like GL_REPEAT: the same value
// as ReliefMap::sample_depth, on a plain float array (this loop is the precompute's hot spot).
class DepthSampler {
 public:
  explicit DepthSampler(const ReliefMap& m) : w_(m.width), h_(m.height), d_(m.relief.size()) {
    for (size_t i = 0; i < d_.size(); ++i) d_[i] = m.relief[i].a;
  }
  double operator()(double x, double y) const {
    // Shift by whole tiles so floor() and % see non-negative values.
    x += 64.0 * w_;
    y += 64.0 * h_;
    const double fx0 = std::floor(x), fy0 = std::floor(y);
    const double fx = x - fx0, fy = y - fy0;
    const long x0 = long(fx0) % w_, y0 = long(fy0) % h_;
    const long x1 = x0 + 1 == w_ ? 0 : x0 + 1, y1 = y0 + 1 == h_ ? 0 : y0 + 1;
    const float* r0 = &d_[size_t(y0) * w_];
    const float* r1 = &d_[size_t(y1) * w_];
    return (r0[x0] * (1 - fx) + r0[x1] * fx) * (1 - fy) + (r1[x0] * (1 - fx) + r1[x1] * fx) * fy;
  }

 private:
  long w_, h_;
  std::vector<float> d_;
};

}  // namespace

SafetyRadii compute_safety_radii(const ReliefMap& map, const SafetyRadiusOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const DepthSampler depth(map);
  SafetyRadii out;
  out.width = map.width;
  out.height = map.height;
  out.radius.assign(size_t(map.width) * map.height, 0);
  const double two_pi = 2 * glm::pi<double>();
  parallel_for(
      out.radius.size(),
      [&](size_t begin, size_t end) {
        for (size_t idx = begin; idx < end; ++idx) {
          const int i = int(idx % map.width), j = int(idx / map.width);
          int radius = o.max_radius;
          for (int d = 0; d < o.directions && radius > 0; ++d) {
            const double theta = two_pi * (d + 0.5) / o.directions;
            const double cx = std::cos(theta), cy = std::sin(theta);
            const bool major_x = std::abs(cx) >= std::abs(cy);
            // Per unit of the major axis (one centerline), the ray moves (ux, uy) texels.
            const double ux = major_x ? (cx > 0 ? 1 : -1) : cx / std::abs(cy);
            const double uy = major_x ? cy / std::abs(cx) : (cy > 0 ? 1 : -1);
            for (int st = 0; st < o.starts && radius > 0; ++st) {
              // Start on the texel's centerline across the major axis, anywhere within the texel.
              const double off = o.starts > 1 ? -0.5 + double(st) / (o.starts - 1) : 0.0;
              const double x0 = i + (major_x ? 0.0 : off), y0 = j + (major_x ? off : 0.0);
              // Texel-centre coordinates -> texture coordinates; height = -depth.
              auto height = [&](int k) {
                const double a = k * o.step;
                return -depth(x0 + ux * a, y0 + uy * a);
              };
              // Only violations before radius + 1 centerlines can lower the radius further.
              const int limit = int(std::ceil((radius + 1) / o.step)) + 1;
              const double s = scan_profile(height, limit, o.step, o.error_allowed);
              if (std::isfinite(s)) radius = std::min(radius, int(std::ceil(s)) - 1);
            }
          }
          out.radius[idx] = uint8_t(std::clamp(radius, 0, 255));
        }
      },
      64);
  out.compute_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

namespace {

std::filesystem::path cache_dir() {
  if (const char* d = std::getenv("RELIEFLAB_CACHE_DIR")) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME")) return std::filesystem::path(d) / "relieflab";
  if (const char* d = std::getenv("HOME")) return std::filesystem::path(d) / ".cache" / "relieflab";
  return std::filesystem::temp_directory_path() / "relieflab-cache";
}

}  // namespace

SafetyRadii cached_safety_radii(const ReliefMap& map, const SafetyRadiusOptions& o) {
  constexpr int kAlgorithmVersion = 1;  // bump when compute_safety_radii changes its answers
  char key_text[256];
  std::snprintf(key_text, sizeof key_text, "v%d|%d|%d|%.9g|%d|%.9g|", kAlgorithmVersion,
                o.directions, o.starts, o.step, o.max_radius, o.error_allowed);
  const std::string key = hex64(fnv1a64(key_text, std::strlen(key_text), map.content_hash()));
  const std::filesystem::path path = cache_dir() / "safety_radius" / (key + ".bin");
  const size_t n = size_t(map.width) * map.height;
  {
    std::ifstream in(path, std::ios::binary);
    if (in) {
      SafetyRadii r;
      r.width = map.width;
      r.height = map.height;
      r.radius.resize(n);
      in.read(reinterpret_cast<char*>(r.radius.data()), std::streamsize(n));
      if (in.gcount() == std::streamsize(n) && in.peek() == EOF) {
        r.from_cache = true;
        return r;
      }
    }
  }
  SafetyRadii r = compute_safety_radii(map, o);
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  if (!ec) {
    // Write then rename: a reader never sees half a file; a failed write only costs a recompute.
    const std::filesystem::path tmp = path.string() + ".tmp" + std::to_string(::getpid());
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      out.write(reinterpret_cast<const char*>(r.radius.data()), std::streamsize(n));
    }
    std::filesystem::rename(tmp, path, ec);
  }
  return r;
}

}  // namespace rl
