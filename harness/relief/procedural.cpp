#include "relief/procedural.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include <glm/gtc/constants.hpp>

#include "core/error.h"

namespace rl {

const std::vector<ProceduralKind>& procedural_kinds() {
  static const std::vector<ProceduralKind> kinds = {
      {"flat", "depth 0 everywhere: every hit lies on the base surface", {}},
      {"constant",
       "one depth everywhere: every hit lies on a plane below the base",
       {{"value", 0.5, "the depth, 0 (top) to 1 (bottom)", 0, 1}}},
      {"sines",
       "smooth bump field d = 0.5 - 0.5 sin(2 pi f u) sin(2 pi f v)",
       {{"frequency", 4, "bumps per tile along u and v", 1, 1024}}},
      {"pyramids",
       "grid of square pyramids with sharp apexes at depth 0 and bases at depth 1",
       {{"count", 8, "pyramids per tile along u and v", 1, 1024}}},
      {"bricks",
       "running-bond bricks at depth 0 with vertical steps down to the mortar",
       {{"rows", 8, "brick rows per tile", 1, 1024},
        {"columns", 4, "bricks per row", 1, 1024},
        {"mortar", 0.08, "mortar width as a fraction of the brick height", 0, 0.5},
        {"mortar_depth", 0.8, "depth of the mortar", 0, 1}}},
      {"domes",
       "spherical caps on a floor at depth 1 (an empty floor under the box proxy: objects "
       "standing on nothing, like a baked mesh)",
       {{"count", 3, "domes per tile along u and v", 1, 1024},
        {"radius", 0.4, "cap radius as a fraction of the dome spacing", 0.01, 0.5}}},
      {"walls",
       "one-texel-thick walls at depth 0 on a grid, floor at depth 1",
       {{"spacing", 16, "texels between walls", 2, 8192}}},
  };
  return kinds;
}

namespace {

using DepthFn = std::function<double(double u, double v, int x, int y)>;

DepthFn depth_function(const std::string& kind, const std::map<std::string, double>& o,
                       int resolution) {
  const double pi = glm::pi<double>();
  if (kind == "flat") return [](double, double, int, int) { return 0.0; };
  if (kind == "constant") {
    double value = o.at("value");
    return [value](double, double, int, int) { return value; };
  }
  if (kind == "sines") {
    double f = o.at("frequency");
    return [f, pi](double u, double v, int, int) {
      return 0.5 - 0.5 * std::sin(2 * pi * f * u) * std::sin(2 * pi * f * v);
    };
  }
  if (kind == "pyramids") {
    double n = o.at("count");
    return [n](double u, double v, int, int) {
      double fu = u * n - std::floor(u * n) - 0.5, fv = v * n - std::floor(v * n) - 0.5;
      return 2.0 * std::max(std::abs(fu), std::abs(fv));
    };
  }
  if (kind == "bricks") {
    double rows = o.at("rows"), cols = o.at("columns"), mortar = o.at("mortar");
    double mortar_depth = o.at("mortar_depth");
    return [=](double u, double v, int, int) {
      double row = std::floor(v * rows);
      double fv = v * rows - row;
      double shifted = u * cols + (static_cast<long long>(row) % 2 ? 0.5 : 0.0);
      double fu = shifted - std::floor(shifted);
      double mortar_u = mortar * cols / rows;  // same world width as the horizontal joints
      bool in_mortar = fv < mortar || fu < mortar_u;
      return in_mortar ? mortar_depth : 0.0;
    };
  }
  if (kind == "domes") {
    double n = o.at("count"), radius = o.at("radius");
    return [n, radius](double u, double v, int, int) {
      double fu = u * n - std::floor(u * n) - 0.5, fv = v * n - std::floor(v * n) - 0.5;
      double r2 = (fu * fu + fv * fv) / (radius * radius);
      return r2 >= 1.0 ? 1.0 : 1.0 - std::sqrt(1.0 - r2);
    };
  }
  if (kind == "walls") {
    int spacing = std::max(2, static_cast<int>(o.at("spacing")));
    (void)resolution;
    return [spacing](double, double, int x, int y) {
      return (x % spacing == 0 || y % spacing == 0) ? 0.0 : 1.0;
    };
  }
  return nullptr;
}

glm::vec3 procedural_color(double u, double v, double depth) {
  // Warm top fading to a dark floor, with a fine checker so that a wrong hit uv shows up in
  // the colour metrics even where depths agree.
  glm::dvec3 top(0.85, 0.62, 0.42), bottom(0.25, 0.22, 0.30);
  glm::dvec3 base = top * (1 - depth) + bottom * depth;
  bool check =
      (static_cast<long long>(std::floor(u * 32)) + static_cast<long long>(std::floor(v * 32))) % 2;
  return glm::vec3(base * (check ? 1.0 : 0.82));
}

}  // namespace

ReliefMap make_procedural(const std::string& kind, int resolution,
                          const std::map<std::string, double>& options, double depth_per_texel,
                          const std::string& where) {
  const ProceduralKind* spec = nullptr;
  for (const auto& k : procedural_kinds())
    if (k.name == kind) spec = &k;
  if (!spec) {
    std::string known;
    for (const auto& k : procedural_kinds()) known += (known.empty() ? "" : ", ") + k.name;
    throw ConfigError(where + ": unknown procedural relief '" + kind + "' (known: " + known + ")");
  }
  if (resolution < 2 || resolution > 8192)
    throw ConfigError(where + ": texture resolution " + std::to_string(resolution) +
                      " is outside [2, 8192]");
  std::map<std::string, double> o;
  for (const auto& opt : spec->options) o[opt.name] = opt.default_value;
  for (const auto& [name, value] : options) {
    auto opt = std::find_if(spec->options.begin(), spec->options.end(),
                            [&](const ProceduralOption& p) { return p.name == name; });
    if (opt == spec->options.end())
      throw ConfigError(where + ": procedural relief '" + kind + "' has no option '" + name + "'");
    if (!(value >= opt->min_value && value <= opt->max_value)) {
      char range[96];
      std::snprintf(range, sizeof range, "[%g, %g], got %g", opt->min_value, opt->max_value, value);
      throw ConfigError(where + ": option '" + name + "' of procedural relief '" + kind +
                        "' must be in " + range);
    }
    o[name] = value;
  }

  DepthFn fn = depth_function(kind, o, resolution);
  ReliefMap map;
  map.name = kind;
  map.width = map.height = resolution;
  map.relief.resize(static_cast<size_t>(resolution) * resolution);
  map.color.resize(map.relief.size());
  for (int y = 0; y < resolution; ++y) {
    for (int x = 0; x < resolution; ++x) {
      double u = (x + 0.5) / resolution, v = (y + 0.5) / resolution;
      double d = std::clamp(fn(u, v, x, y), 0.0, 1.0);
      map.relief[map.index(x, y)] = glm::vec4(0.5f, 0.5f, 1.0f, static_cast<float>(d));
      map.color[map.index(x, y)] = glm::vec4(procedural_color(u, v, d), 1.0f);
    }
  }
  normals_from_depth(map, depth_per_texel);
  return map;
}

}  // namespace rl
