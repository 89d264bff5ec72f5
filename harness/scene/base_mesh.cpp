#include "scene/base_mesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include <Eigen/Dense>
#include <glm/gtc/constants.hpp>

#include "core/data_paths.h"
#include "core/error.h"
#include "relief/mesh_bake.h"

namespace rl {
namespace {

// The generated torus's radii as fractions of the base's size (its bounding diameter).
constexpr double kTorusMajor = 0.35, kTorusMinor = 0.15;

constexpr double kPi = glm::pi<double>();

SurfaceChart sphere_chart(double radius, double tile, int segments) {
  // u around the z axis (two tiles: the equator is twice the pole-to-pole arc), v from the
  // south pole to the north pole; T x B = N outward.
  SurfaceChart c;
  c.uv_max = {2 * tile, tile};
  c.segments_u = segments;
  c.segments_v = std::max(2, segments / 2);
  c.eval = [=](const glm::dvec2& uv, glm::dvec3& p, glm::dvec3& n) {
    const double phi = kPi * uv.x / tile, theta = kPi * uv.y / tile;
    n = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), -std::cos(theta)};
    p = radius * n;
  };
  return c;
}

SurfaceChart torus_chart(double major, double minor, double tile, int segments) {
  // u around the main circle in the xy plane, v around the tube (starting outside).
  SurfaceChart c;
  c.uv_max = {2 * tile, tile};
  c.segments_u = segments;
  c.segments_v = std::max(3, segments / 2);
  c.eval = [=](const glm::dvec2& uv, glm::dvec3& p, glm::dvec3& n) {
    const double phi = kPi * uv.x / tile, psi = 2 * kPi * uv.y / tile;
    n = {std::cos(psi) * std::cos(phi), std::cos(psi) * std::sin(phi), std::sin(psi)};
    p = glm::dvec3(major * std::cos(phi), major * std::sin(phi), 0) + minor * n;
  };
  return c;
}

SurfaceChart flat_chart(const glm::dvec3& center, const glm::dvec3& t, const glm::dvec3& b,
                        double side, double tile, int segments) {
  SurfaceChart c;
  c.uv_max = {tile, tile};
  c.segments_u = c.segments_v = segments;
  const glm::dvec3 n = glm::cross(t, b);
  c.eval = [=](const glm::dvec2& uv, glm::dvec3& p, glm::dvec3& normal) {
    p = center + t * ((uv.x / tile - 0.5) * side) + b * ((uv.y / tile - 0.5) * side);
    normal = n;
  };
  return c;
}

// Samples every chart on its segment grid into one mesh.
void mesh_charts(BaseMesh& m) {
  for (const SurfaceChart& c : m.charts) {
    const unsigned first = unsigned(m.position.size());
    for (int j = 0; j <= c.segments_v; ++j)
      for (int i = 0; i <= c.segments_u; ++i) {
        const glm::dvec2 f(double(i) / c.segments_u, double(j) / c.segments_v);
        const glm::dvec2 uv = c.uv_min + (c.uv_max - c.uv_min) * f;
        glm::dvec3 p, n;
        c.eval(uv, p, n);
        m.position.push_back(p);
        m.normal.push_back(n);
        m.uv.push_back(uv);
      }
    const unsigned row = unsigned(c.segments_u) + 1;
    for (int j = 0; j < c.segments_v; ++j)
      for (int i = 0; i < c.segments_u; ++i) {
        const unsigned a = first + j * row + i, b = a + 1, d = a + row, e = d + 1;
        m.triangles.push_back({a, b, e});
        m.triangles.push_back({a, e, d});
      }
  }
}

double corner_angle(const glm::dvec3& at, const glm::dvec3& p, const glm::dvec3& q) {
  const glm::dvec3 a = p - at, b = q - at;
  const double la = glm::length(a), lb = glm::length(b);
  if (la == 0 || lb == 0) return 0;
  return std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0));
}

// Groups vertices at the same position (to 1e-7 of the mesh's size): seams and poles.
std::vector<unsigned> weld_by_position(const std::vector<glm::dvec3>& positions, double scale) {
  std::map<std::tuple<long long, long long, long long>, unsigned> groups;
  std::vector<unsigned> group(positions.size());
  const double q = 1e-7 * std::max(scale, 1e-30);
  for (size_t i = 0; i < positions.size(); ++i) {
    const auto key =
        std::make_tuple(std::llround(positions[i].x / q), std::llround(positions[i].y / q),
                        std::llround(positions[i].z / q));
    group[i] = groups.emplace(key, unsigned(groups.size())).first->second;
  }
  return group;
}

// Angle-weighted vertex normals over the welded mesh.
void compute_normals(BaseMesh& m) {
  const std::vector<unsigned> group = weld_by_position(m.position, m.radius);
  std::vector<glm::dvec3> sum(m.position.size(), glm::dvec3(0));
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 &p0 = m.position[t.x], &p1 = m.position[t.y], &p2 = m.position[t.z];
    const glm::dvec3 face = glm::cross(p1 - p0, p2 - p0);
    if (glm::length(face) == 0) continue;
    const glm::dvec3 n = glm::normalize(face);
    sum[group[t.x]] += n * corner_angle(p0, p1, p2);
    sum[group[t.y]] += n * corner_angle(p1, p2, p0);
    sum[group[t.z]] += n * corner_angle(p2, p0, p1);
  }
  m.normal.resize(m.position.size());
  for (size_t i = 0; i < m.position.size(); ++i) {
    const glm::dvec3 s = sum[group[i]];
    m.normal[i] = glm::length(s) > 0 ? glm::normalize(s) : glm::dvec3(0, 0, 1);
  }
}

// Centres the mesh on its bounding box and scales it into a sphere of radius size / 2.
void fit_into_sphere(std::vector<glm::dvec3>& positions, double size) {
  glm::dvec3 lo = positions[0], hi = positions[0];
  for (const auto& p : positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::dvec3 c = 0.5 * (lo + hi);
  double r = 0;
  for (const auto& p : positions) r = std::max(r, glm::length(p - c));
  for (auto& p : positions) p = (p - c) * (0.5 * size / std::max(r, 1e-30));
}

// The teapot file has no uvs: a cylindrical projection about its (z) axis, u twice around as
// for the sphere, v up the axis at the same world scale. Triangles across the seam get copies
// of their vertices with u shifted by one turn; vertices on the axis take the u of their
// triangle's other corners (the projection is singular there).
void cylindrical_uvs(const std::vector<glm::dvec3>& positions,
                     const std::vector<glm::uvec3>& triangles, double tile, BaseMesh& m) {
  double z_lo = positions[0].z, mean_r = 0;
  for (const auto& p : positions) {
    z_lo = std::min(z_lo, p.z);
    mean_r += std::hypot(p.x, p.y) / positions.size();
  }
  const double turn = 2 * tile;
  auto base_u = [&](const glm::dvec3& p) {
    return (std::atan2(p.y, p.x) / (2 * kPi) + 0.5) * turn;
  };
  std::map<std::pair<unsigned, long long>, unsigned> copies;  // (vertex, u in 1e-9) -> index
  for (const glm::uvec3& t : triangles) {
    double u[3];
    bool on_axis[3];
    double u_sum = 0;
    int off_axis = 0;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3& p = positions[t[k]];
      on_axis[k] = std::hypot(p.x, p.y) < 1e-9 * (mean_r + 1e-30);
      u[k] = base_u(p);
    }
    // Unwrap across the seam relative to the first off-axis corner.
    double ref = 0;
    for (int k = 0; k < 3; ++k)
      if (!on_axis[k]) {
        ref = u[k];
        break;
      }
    for (int k = 0; k < 3; ++k) {
      if (on_axis[k]) continue;
      if (u[k] - ref > 0.5 * turn) u[k] -= turn;
      if (ref - u[k] > 0.5 * turn) u[k] += turn;
      u_sum += u[k];
      ++off_axis;
    }
    for (int k = 0; k < 3; ++k)
      if (on_axis[k]) u[k] = off_axis ? u_sum / off_axis : 0;
    glm::uvec3 out;
    for (int k = 0; k < 3; ++k) {
      const auto key = std::make_pair(t[k], std::llround(u[k] * 1e9));
      auto it = copies.find(key);
      if (it == copies.end()) {
        const glm::dvec3& p = positions[t[k]];
        it = copies.emplace(key, unsigned(m.position.size())).first;
        m.position.push_back(p);
        m.uv.push_back({u[k], (p.z - z_lo) * tile / (kPi * mean_r)});
      }
      out[k] = it->second;
    }
    m.triangles.push_back(out);
  }
}

BaseMesh mesh_from_file(const TriangleMesh& file, bool generate_uvs, double size, double tile,
                        bool z_from_y) {
  if (!generate_uvs) check_base_uvs(file);
  std::vector<glm::dvec3> positions;
  for (const glm::vec3& p : file.positions)
    positions.push_back(z_from_y ? glm::dvec3(p.x, -p.z, p.y) : glm::dvec3(p));
  fit_into_sphere(positions, size);
  BaseMesh m;
  m.radius = 0.5 * size;
  if (generate_uvs) {
    std::vector<glm::uvec3> triangles(file.triangles.begin(), file.triangles.end());
    cylindrical_uvs(positions, triangles, tile, m);
  } else {
    m.position = positions;
    for (const glm::vec2& uv : file.uvs) m.uv.push_back(glm::dvec2(uv) * tile);
    m.triangles = file.triangles;
  }
  compute_normals(m);
  return m;
}

}  // namespace

// A base mesh's own texture coordinates must map the relief: near enough to the origin that a
// float still tells texels apart, and spanning some area (all-equal uvs map every point of the
// surface to one texel).
void check_base_uvs(const TriangleMesh& file) {
  constexpr float kLargestUv = 1024;  // float spacing there: 1.2e-4, an eighth of a 1024 texel
  for (size_t i = 0; i < file.uvs.size(); ++i) {
    const glm::vec2 uv = file.uvs[i];
    if (!(std::abs(uv.x) <= kLargestUv && std::abs(uv.y) <= kLargestUv)) {
      char text[200];
      std::snprintf(text, sizeof text,
                    ": texture coordinate %zu is (%.6g, %.6g), beyond +-1024 (float precision "
                    "there cannot tell texels apart); bring the uvs near [0, 1]",
                    i, double(uv.x), double(uv.y));
      throw ConfigError("base mesh " + file.name + text);
    }
  }
  for (const glm::uvec3& t : file.triangles) {
    const glm::dvec2 a(file.uvs[t.x]), b(file.uvs[t.y]), c(file.uvs[t.z]);
    if ((b - a).x * (c - a).y - (c - a).x * (b - a).y != 0) return;
  }
  throw ConfigError("base mesh " + file.name +
                    ": every triangle has zero area in texture space (are all its texture "
                    "coordinates equal?): it maps no relief; give it a uv mapping, or remove "
                    "its uvs to have them generated");
}

BaseMesh make_base_mesh(const BaseDesc& desc, double size, double tile, bool require_uvs) {
  BaseMesh m;
  const int segments = std::max(3, desc.segments);
  if (desc.kind == "plane") {
    m.charts.push_back(flat_chart({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, size, tile, 1));
  } else if (desc.kind == "sphere") {
    m.charts.push_back(sphere_chart(0.5 * size, tile, segments));
  } else if (desc.kind == "torus") {
    m.charts.push_back(torus_chart(kTorusMajor * size, kTorusMinor * size, tile, segments));
  } else if (desc.kind == "cube") {
    // Side such that the corners lie on the sphere of diameter `size`; each face's (u, v)
    // axes with u x v = its outward normal. Faces are split so that only the vertices on the
    // cube's edges see the neighbouring faces in their ring.
    const double side = size / std::sqrt(3.0), h = 0.5 * side;
    const int s = std::max(1, segments / 8);
    const glm::dvec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
    const glm::dvec3 faces[6][2] = {{y, z}, {-y, z}, {z, x}, {-z, x}, {x, y}, {-x, y}};
    for (const auto& f : faces)
      m.charts.push_back(flat_chart(glm::cross(f[0], f[1]) * h, f[0], f[1], side, tile, s));
  } else if (desc.kind == "teapot" || desc.kind == "file") {
    const bool teapot = desc.kind == "teapot";
    const std::string path = teapot ? data_root() + "/assets/meshes/teapot.obj" : desc.path;
    const TriangleMesh file = load_mesh(path);
    if (!teapot && require_uvs && file.uvs.empty())
      throw ConfigError("base mesh " + path +
                        " has no texture coordinates; a relief needs a uv mapping");
    m = mesh_from_file(file, file.uvs.empty(), size, tile, teapot);
  } else {
    throw ConfigError("unknown base '" + desc.kind +
                      "' (known: plane, cube, sphere, torus, teapot, or a mesh file)");
  }
  if (!m.charts.empty()) {
    m.radius = 0.5 * size;
    mesh_charts(m);
  }
  compute_tangent_frames(m);
  compute_curvature(m);
  return m;
}

double texel_world(const SceneDesc& scene, int res) {
  if (scene.cell_complex()) return scene.size / kCellMetricTexels;
  const MapSize size = scene.relief.size_at(res);
  if (!scene.base.curved()) return planar_base(scene).texel_world(size.width);
  return texel_world(make_base_mesh(scene.base, scene.size, scene.tile), size);
}

BaseGeometry base_geometry(const BaseMesh& mesh) {
  BaseGeometry g;
  for (size_t i = 0; i < mesh.position.size(); ++i) {
    BaseVertex v;
    v.position = glm::vec3(mesh.position[i]);
    v.uv = glm::vec2(mesh.uv[i]);
    v.dpdu = glm::vec3(mesh.dpdu[i]);
    v.dpdv = glm::vec3(mesh.dpdv[i]);
    v.normal = glm::vec3(mesh.normal[i]);
    v.entry_depth = 0;
    v.curvature = glm::vec2(mesh.curvature[i]);
    g.vertices.push_back(v);
  }
  for (const glm::uvec3& t : mesh.triangles) g.indices.insert(g.indices.end(), {t.x, t.y, t.z});
  return g;
}

double texel_world(const BaseMesh& m, const MapSize& size) {
  double sum = 0;
  for (size_t i = 0; i < m.position.size(); ++i)
    sum += 0.5 * (glm::length(m.dpdu[i]) / size.width + glm::length(m.dpdv[i]) / size.height);
  return sum / std::max<size_t>(1, m.position.size());
}

void uv_frame(const glm::dvec3& n, const glm::dvec3& du, const glm::dvec3& dv, glm::dvec3& t,
              glm::dvec3& b) {
  t = du - n * glm::dot(n, du);
  if (!(glm::length(t) > 1e-12 * glm::length(du)) || glm::length(t) == 0) {
    // No usable u direction (a pole): any tangent; the mapping scale says how bad it is.
    t = std::abs(n.x) < 0.9 ? glm::cross(n, glm::dvec3(1, 0, 0))
                            : glm::cross(n, glm::dvec3(0, 1, 0));
  }
  t = glm::normalize(t);
  b = glm::cross(n, t);
  if (glm::dot(b, dv) < 0) b = -b;  // mirrored uvs
}

void compute_tangent_frames(BaseMesh& m) {
  const size_t n = m.position.size();
  std::vector<glm::dvec3> dir_u(n, glm::dvec3(0)), dir_v(n, glm::dvec3(0));
  std::vector<double> len_u(n, 0), len_v(n, 0), weight(n, 0);
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 e1 = m.position[t.y] - m.position[t.x];
    const glm::dvec3 e2 = m.position[t.z] - m.position[t.x];
    const glm::dvec2 d1 = m.uv[t.y] - m.uv[t.x], d2 = m.uv[t.z] - m.uv[t.x];
    const double det = d1.x * d2.y - d2.x * d1.y;
    if (std::abs(det) < 1e-300) continue;  // degenerate in uv: no mapping to learn from
    const glm::dvec3 du = (e1 * d2.y - e2 * d1.y) / det;
    const glm::dvec3 dv = (e2 * d1.x - e1 * d2.x) / det;
    for (int k = 0; k < 3; ++k) {
      const unsigned i = t[k];
      const double w =
          corner_angle(m.position[i], m.position[t[(k + 1) % 3]], m.position[t[(k + 2) % 3]]);
      dir_u[i] += w * du;
      dir_v[i] += w * dv;
      len_u[i] += w * glm::length(du);
      len_v[i] += w * glm::length(dv);
      weight[i] += w;
    }
  }
  m.dpdu.resize(n);
  m.dpdv.resize(n);
  for (size_t i = 0; i < n; ++i) {
    glm::dvec3 T, B;
    uv_frame(m.normal[i], dir_u[i], dir_v[i], T, B);
    // A floor on the scale keeps the frame usable where the mapping collapses (poles): the
    // shaders then see a huge but finite texture-space direction.
    const double w = weight[i] > 0 ? weight[i] : 1, floor = 1e-9 * std::max(m.radius, 1e-30);
    m.dpdu[i] = T * std::max(len_u[i] / w, floor);
    m.dpdv[i] = B * std::max(len_v[i] / w, floor);
  }
}

glm::dvec2 fit_quadric(const std::vector<glm::dvec3>& ring) {
  if (ring.size() < 3) return {0, 0};
  Eigen::MatrixXd E(ring.size(), 2);
  Eigen::VectorXd F(ring.size());
  for (size_t i = 0; i < ring.size(); ++i) {
    E(i, 0) = ring[i].x * ring[i].x;
    E(i, 1) = ring[i].y * ring[i].y;
    F(i) = -ring[i].z;
  }
  const Eigen::Vector2d ab = E.completeOrthogonalDecomposition().solve(F);
  if (!std::isfinite(ab(0)) || !std::isfinite(ab(1))) return {0, 0};
  return {ab(0), ab(1)};
}

void compute_curvature(BaseMesh& m) {
  const std::vector<unsigned> group = weld_by_position(m.position, m.radius);
  const unsigned groups = group.empty() ? 0 : *std::max_element(group.begin(), group.end()) + 1;
  std::vector<std::set<unsigned>> ring(groups);
  std::vector<glm::dvec3> where(groups);
  for (size_t i = 0; i < m.position.size(); ++i) where[group[i]] = m.position[i];
  for (const glm::uvec3& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const unsigned a = group[t[k]], b = group[t[(k + 1) % 3]];
      if (a == b) continue;
      ring[a].insert(b);
      ring[b].insert(a);
    }
  m.curvature.resize(m.position.size());
  for (size_t i = 0; i < m.position.size(); ++i) {
    const glm::dvec3 T = glm::normalize(m.dpdu[i]), B = glm::normalize(m.dpdv[i]), N = m.normal[i];
    std::vector<glm::dvec3> local;
    for (unsigned g : ring[group[i]]) {
      const glm::dvec3 q = where[g] - m.position[i];
      local.push_back({glm::dot(q, T), glm::dot(q, B), glm::dot(q, N)});
    }
    m.curvature[i] = fit_quadric(local);
  }
}

std::optional<CurvatureFitError> curvature_fit_error(const BaseDesc& desc, const BaseMesh& m) {
  const bool sphere = desc.kind == "sphere", torus = desc.kind == "torus";
  if ((!sphere && !torus) || m.position.empty()) return std::nullopt;
  const double size = 2 * m.radius;
  const double major = kTorusMajor * size, minor = kTorusMinor * size;
  CurvatureFitError e;
  long signs = 0, matched = 0;
  for (size_t i = 0; i < m.position.size(); ++i) {
    glm::dvec2 exact(1 / size);  // the sphere: 1 / (2 R), R = size / 2
    if (torus) {
      // Around the main circle cos(v) / rho (negative inside the hole), around the tube 1 / r.
      const double rho = std::hypot(m.position[i].x, m.position[i].y);
      exact = {(rho - major) / (2 * minor * rho), 1 / (2 * minor)};
    }
    const glm::dvec2 fit = m.curvature[i];
    const double scale = std::max(std::abs(exact.x), std::abs(exact.y));
    const double err = 100 * std::max(std::abs(fit.x - exact.x), std::abs(fit.y - exact.y)) / scale;
    e.mean_pct += err;
    e.max_pct = std::max(e.max_pct, err);
    for (int k = 0; k < 2; ++k)
      if (std::abs(exact[k]) >= 0.05 * scale) {
        ++signs;
        matched += (fit[k] > 0) == (exact[k] > 0);
      }
  }
  e.mean_pct /= double(m.position.size());
  e.sign_match_pct = signs > 0 ? 100.0 * double(matched) / double(signs) : 100.0;
  return e;
}

}  // namespace rl
