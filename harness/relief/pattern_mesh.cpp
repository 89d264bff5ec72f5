#include "relief/pattern_mesh.h"

#include <cmath>
#include <functional>

#include "core/error.h"

namespace rl {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A closed curve over s in [0, 1] in texture space (x = u, y = v, z = depth), periodic up to a
// whole-tile offset, and the half-extents of its elliptical cross-section.
struct Thread {
  std::function<glm::dvec3(double)> curve;
  double half_width = 0.1;      // along the horizontal binormal
  double half_thickness = 0.1;  // along the normal
  glm::vec3 color{0.8f};
};

// Sweeps the thread's cross-section along its curve. The frame (T, B = T x up, N = B x T)
// depends only on the tangent, which is periodic, so the ring at s = 1 is the ring at s = 0
// moved by one tile: the tube continues seamlessly into the next tile. In mesh space (z =
// -depth, right-handed) triangles wind so their normals point out of the tube.
void sweep_tube(TriangleMesh& mesh, const Thread& thread, int segments, int sides) {
  const uint32_t first = uint32_t(mesh.positions.size());
  auto at = [&](double s) {  // in mesh space, z = -depth
    const glm::dvec3 p = thread.curve(s);
    return glm::dvec3(p.x, p.y, -p.z);
  };
  const double h = 1e-5;
  for (int i = 0; i <= segments; ++i) {
    const double s = double(i) / segments;
    const glm::dvec3 c = at(s);
    const glm::dvec3 t = glm::normalize(at(s + h) - at(s - h));
    const glm::dvec3 b = glm::normalize(glm::cross(t, glm::dvec3(0, 0, 1)));
    const glm::dvec3 n = glm::cross(b, t);
    for (int k = 0; k < sides; ++k) {
      const double a = 2 * kPi * k / sides;
      const glm::dvec3 p =
          c + b * (thread.half_width * std::cos(a)) + n * (thread.half_thickness * std::sin(a));
      mesh.positions.emplace_back(p);
    }
  }
  for (int i = 0; i < segments; ++i)
    for (int k = 0; k < sides; ++k) {
      const uint32_t a = first + i * sides + k, b = first + i * sides + (k + 1) % sides;
      const uint32_t c = a + sides, d = b + sides;
      mesh.triangles.emplace_back(a, c, b);
      mesh.triangles.emplace_back(b, c, d);
      mesh.triangle_colors.push_back(thread.color);
      mesh.triangle_colors.push_back(thread.color);
    }
}

}  // namespace

const std::vector<std::string>& pattern_mesh_kinds() {
  static const std::vector<std::string> kinds = {"weave", "helix"};
  return kinds;
}

bool is_pattern_mesh(const std::string& kind) {
  for (const std::string& k : pattern_mesh_kinds())
    if (k == kind) return true;
  return false;
}

std::map<std::string, double> pattern_mesh_defaults(const std::string& kind) {
  if (kind == "weave")
    return {{"threads", 2},      {"width", 0.3},    {"thickness", 0.14},
            {"amplitude", 0.25}, {"segments", 128}, {"sides", 16}};
  if (kind == "helix")
    return {{"helices", 2},      {"strands", 2},    {"turns", 1}, {"radius", 0.12},
            {"thickness", 0.05}, {"segments", 128}, {"sides", 12}};
  return {};
}

namespace {

// A pattern's options, defaults filled in, with the checks every kind makes.
struct PatternOptions {
  std::string kind, where;
  std::map<std::string, double> values;
  int segments = 0, sides = 0;

  double value(const std::string& key) const { return values.at(key); }
  int positive_int(const std::string& key, int lo, int hi) const {
    const double v = values.at(key);
    if (v != std::floor(v) || v < lo || v > hi)
      throw ConfigError(where + ": " + kind + " option '" + key + "' must be an integer in [" +
                        std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return int(v);
  }
  // The bake and the truth trace every triangle (9 tiles' worth on the plane): keep a tile
  // within a few million.
  void check_budget(int tubes) const {
    const double triangles = 2.0 * tubes * segments * sides;
    if (triangles > 4e6)
      throw ConfigError(where + ": " + kind + " options give " + std::to_string(long(triangles)) +
                        " triangles per tile (at most 4,000,000); lower 'segments' or 'sides'");
  }
};

const glm::vec3 kWarp(0.80f, 0.36f, 0.22f), kWeft(0.25f, 0.45f, 0.78f);

// Threads along u and along v, each over and under the ones it crosses.
void add_weave(const PatternOptions& o, TriangleMesh& mesh) {
  const int segments = o.segments, sides = o.sides;
  const int threads = o.positive_int("threads", 2, 64);
  if (threads % 2) throw ConfigError(o.where + ": weave option 'threads' must be even");
  o.check_budget(2 * threads);
  const double w = o.value("width") / 2, th = o.value("thickness") / 2, amp = o.value("amplitude");
  const double spacing = 1.0 / threads;
  // Threads of one direction never touch (width < spacing); at a crossing the upper thread
  // is 2 amp above the lower one at their centres and 2 amp cos(pi threads w) at the corners
  // of the overlap, which must clear both tubes' thickness.
  if (w <= 0 || th <= 0 || 2 * w >= spacing || amp * std::cos(kPi * threads * w) <= 1.05 * th ||
      amp + th >= 0.5)
    throw ConfigError(o.where +
                      ": weave options make threads intersect or leave the depth range "
                      "(need width < 1/threads, amplitude cos(pi threads width/2) > "
                      "1.05 thickness/2, amplitude + thickness/2 < 0.5)");
  for (int j = 0; j < threads; ++j) {
    const double c = (j + 0.5) * spacing, phase = kPi * j;
    // Along u, over thread i (at u = (i + 0.5) spacing) when i + j is even.
    sweep_tube(mesh,
               {[=](double s) {
                  return glm::dvec3(s, c, 0.5 - amp * std::sin(kPi * threads * s + phase));
                },
                w, th, kWarp},
               segments, sides);
    sweep_tube(mesh,
               {[=](double s) {
                  return glm::dvec3(c, s, 0.5 + amp * std::sin(kPi * threads * s + phase));
                },
                w, th, kWeft},
               segments, sides);
  }
}

// Helices along u, one or two strands each.
void add_helices(const PatternOptions& o, TriangleMesh& mesh) {
  const int segments = o.segments, sides = o.sides;
  const int helices = o.positive_int("helices", 1, 64), strands = o.positive_int("strands", 1, 2);
  const int turns = o.positive_int("turns", 1, 64);
  o.check_budget(helices * strands);
  const double r = o.value("radius"), th = o.value("thickness");
  const double spacing = 1.0 / helices;
  if (r <= 0 || th <= 0 || r + th >= 0.5 * spacing || (strands == 2 && th >= r) || r + th >= 0.5)
    throw ConfigError(o.where +
                      ": helix options make strands intersect or leave the tile "
                      "(need radius + thickness < 1/(2 helices), thickness < radius)");
  for (int j = 0; j < helices; ++j)
    for (int k = 0; k < strands; ++k) {
      const double c = (j + 0.5) * spacing, phase = kPi * k;
      sweep_tube(mesh,
                 {[=](double s) {
                    const double a = 2 * kPi * turns * s + phase;
                    return glm::dvec3(s, c + r * std::cos(a), 0.5 + r * std::sin(a));
                  },
                  th, th, k ? kWeft : kWarp},
                 segments, sides);
    }
}

}  // namespace

TriangleMesh make_pattern_mesh(const std::string& kind, std::map<std::string, double> options,
                               const std::string& where) {
  PatternOptions o{kind, where, pattern_mesh_defaults(kind)};
  if (o.values.empty()) throw ConfigError(where + ": unknown pattern mesh '" + kind + "'");
  for (const auto& [key, value] : options) {
    if (!o.values.count(key))
      throw ConfigError(where + ": pattern '" + kind + "' has no option '" + key + "'");
    o.values[key] = value;
  }
  o.segments = o.positive_int("segments", 8, 4096);
  o.sides = o.positive_int("sides", 3, 256);
  TriangleMesh mesh;
  mesh.name = kind;
  if (kind == "weave")
    add_weave(o, mesh);
  else
    add_helices(o, mesh);
  mesh.lo = glm::dvec3(mesh.positions[0]);
  mesh.hi = mesh.lo;
  for (const glm::vec3& p : mesh.positions) {
    mesh.lo = glm::min(mesh.lo, glm::dvec3(p));
    mesh.hi = glm::max(mesh.hi, glm::dvec3(p));
  }
  return mesh;
}

TriangleMesh with_neighbour_tiles(const TriangleMesh& tile) {
  TriangleMesh out;
  out.name = tile.name;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const uint32_t first = uint32_t(out.positions.size());
      for (const glm::vec3& p : tile.positions) out.positions.push_back(p + glm::vec3(dx, dy, 0));
      for (const glm::uvec3& t : tile.triangles) out.triangles.push_back(t + glm::uvec3(first));
      out.triangle_colors.insert(out.triangle_colors.end(), tile.triangle_colors.begin(),
                                 tile.triangle_colors.end());
    }
  out.lo = tile.lo - glm::dvec3(1, 1, 0);
  out.hi = tile.hi + glm::dvec3(1, 1, 0);
  return out;
}

}  // namespace rl
