// Building a cubic cell complex from a closed mesh (Apaza & Andujar, Section 3.3: classify the
// grid, choose each grey cell's configuration, sample the domain faces' relief maps) and reading
// it back (the lookup and samples the truth and the tests use).
#include "relief/cell_complex.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <memory>
#include <stdexcept>

#include <embree3/rtcore.h>

#include "core/columns.h"
#include "core/elapsed.h"
#include "core/embree_util.h"
#include "core/error.h"
#include "core/parallel.h"

namespace rl {
namespace {

// A cubic cell complex's columns (Apaza & Andujar; the sweep writes them from Stats).
const ColumnDeclaration cell_complex_columns(
    "relief (cell complex)",
    {ColumnSpec{"cell_grid", "cells", "cells per side of the cell complex's grid"}.neither_better(),
     ColumnSpec{"mesh_faces", "triangles", "triangles of the mesh the cell complex encodes"}
         .neither_better(),
     ColumnSpec{"grey_cells", "cells", "cells the surface passes through"}.neither_better(),
     ColumnSpec{"domain_faces", "faces", "faces of the grey cells' domain, one relief map each"}
         .neither_better(),
     {"cell_bytes", "bytes", "GPU memory of the cell complex's textures and buffers"},
     {"cell_classify_ms", "ms", "time to classify the grid's cells"},
     {"cell_sample_ms", "ms", "time to sample the domain faces' relief maps"},
     {"cell_construction_ms", "ms",
      "time to build the cell complex, grid choice included (also when read from cache)"},
     {"cell_from_cache", "", "the cell complex came from the precompute cache", ColumnKind::Flag},
     {"cell_distance_bytes", "bytes", "memory of the distance data for empty-space skipping"},
     {"cell_ambiguous_regions", "regions",
      "non-grey regions whose inside / outside votes disagreed (an open or non-manifold mesh)"},
     {"occluded_fragment_pct", "% of fragments",
      "surface crossings of the texels' projection lines hidden behind a first crossing "
      "(Section 3.3.3's occluded fragments)"},
     {"multi_crossing_pct", "% of texels",
      "domain-face texels whose projection line crosses the surface more than once"},
     ColumnSpec{"texels_perspective_pct", "% of texels",
                "domain-face texels of cells with a perspective projection (Figure 2)"}
         .neither_better(),
     ColumnSpec{"texels_axial_pct", "% of texels", "the same, axial projection"}.neither_better(),
     ColumnSpec{"texels_planar_pct", "% of texels", "the same, planar projection"}.neither_better(),
     ColumnSpec{"texels_parallel_pct", "% of texels", "the same, parallel projection"}
         .neither_better(),
     {"multi_crossing_perspective_pct", "% of texels",
      "of the texels of cells with a perspective projection, those whose line crosses the "
      "surface more than once (where the projection does not make the cell's surface a "
      "height field)"},
     {"multi_crossing_axial_pct", "% of texels", "the same, axial projection"},
     {"multi_crossing_planar_pct", "% of texels", "the same, planar projection"},
     {"multi_crossing_parallel_pct", "% of texels", "the same, parallel projection"},
     {"grid_trials", "", "each grid an automatic choice tried, N:occluded %", ColumnKind::Text},
     ColumnSpec{"intersections_per_s", "1/s", "covered pixels per second of frame time"}
         .higher_is_better()});

}  // namespace

namespace {

int popcount6(unsigned m) {
  int c = 0;
  for (int f = 0; f < 6; ++f) c += (m >> f) & 1u;
  return c;
}

// Fragments along a segment: every surface crossing of o + t d, t in [0, t_max] (d unit),
// up to kMaxCrossings; the first one's geometry in `first`.
constexpr int kMaxCrossings = 64;
int count_crossings(RTCScene scene, const glm::dvec3& o, const glm::dvec3& d, double t_max,
                    RTCRayHit* first) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  int n = 0;
  double t0 = 0;
  while (n < kMaxCrossings) {
    RTCRayHit rh = embree_ray(o, d, t0, t_max);
    rtcIntersect1(scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
    if (n == 0 && first) *first = rh;
    ++n;
    // Past this crossing: a relative step, so a shared edge is not counted twice but the next
    // sheet (at least float rounding away) is.
    t0 = double(rh.ray.tfar) + 1e-6 * std::max(1.0, t_max);
  }
  return n;
}

// Inside by the parity of crossings out to beyond the cube, voted over three directions.
// Returns the majority; `agreed` false when the votes differ (an open or non-manifold mesh).
bool parity_inside(RTCScene scene, const glm::dvec3& p, bool* agreed) {
  // Directions off the axes so rays do not run along the grid's (and a CAD mesh's) planes.
  static const glm::dvec3 dirs[3] = {glm::normalize(glm::dvec3(1, 0.0123, 0.0271)),
                                     glm::normalize(glm::dvec3(-0.0317, 1, 0.0149)),
                                     glm::normalize(glm::dvec3(0.0213, -0.0371, -1))};
  int votes = 0;
  for (const glm::dvec3& d : dirs) votes += count_crossings(scene, p, d, 4.0, nullptr) % 2;
  if (agreed) *agreed = votes == 0 || votes == 3;
  return votes >= 2;
}

struct EmbreeScene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  explicit EmbreeScene(const TriangleMesh& mesh) {
    device = rtcNewDevice(nullptr);
    scene = embree_triangle_scene(device, mesh);
  }
  ~EmbreeScene() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
};

// Bilinear weights of face coordinates st on a res x res map with texel centres at
// (i + 0.5) / res, clamped to the outer centres (a face's map does not wrap).
struct Bilinear {
  int x0, y0, x1, y1;
  double fx, fy;
};
Bilinear bilinear(glm::dvec2 st, int res) {
  const double x = std::clamp(st.x * res - 0.5, 0.0, double(res - 1));
  const double y = std::clamp(st.y * res - 0.5, 0.0, double(res - 1));
  Bilinear b;
  b.x0 = std::min(int(x), res - 1);
  b.y0 = std::min(int(y), res - 1);
  b.x1 = std::min(b.x0 + 1, res - 1);
  b.y1 = std::min(b.y0 + 1, res - 1);
  b.fx = x - b.x0;
  b.fy = y - b.y0;
  return b;
}

}  // namespace

namespace {

// Classification (Section 3.3.1): grey by exact triangle-box overlap; white and black by a
// flood fill from the grid's border through non-grey cells, each enclosed region decided by
// parity rays from one of its cells.
void classify(const TriangleMesh& mesh, RTCScene scene, int n,
              std::vector<CellComplex::Cell>& cells, CellComplex::Stats& stats) {
  const size_t count = size_t(n) * n * n;
  auto grey = std::make_unique<std::atomic<uint8_t>[]>(count);
  for (size_t i = 0; i < count; ++i) grey[i].store(0, std::memory_order_relaxed);
  std::atomic<long> degenerate{0};
  const double pad = 1e-9;  // closed boxes, and a hair more: touching is grey
  parallel_for(
      mesh.triangles.size(),
      [&](size_t begin, size_t end) {
        for (size_t t = begin; t < end; ++t) {
          const glm::uvec3 tri = mesh.triangles[t];
          const glm::dvec3 a(mesh.positions[tri.x]), b(mesh.positions[tri.y]),
              c(mesh.positions[tri.z]);
          if (glm::length(glm::cross(b - a, c - a)) < 1e-18) {
            ++degenerate;  // no area: it bounds nothing (its edges belong to its neighbours)
            continue;
          }
          const glm::dvec3 lo = glm::min(a, glm::min(b, c)) * double(n),
                           hi = glm::max(a, glm::max(b, c)) * double(n);
          glm::ivec3 i0, i1;
          for (int k = 0; k < 3; ++k) {
            i0[k] = std::clamp(int(std::floor(lo[k] - 1e-7)), 0, n - 1);
            i1[k] = std::clamp(int(std::floor(hi[k] + 1e-7)), 0, n - 1);
          }
          for (int k = i0.z; k <= i1.z; ++k)
            for (int j = i0.y; j <= i1.y; ++j)
              for (int i = i0.x; i <= i1.x; ++i) {
                const size_t idx = (size_t(k) * n + j) * n + i;
                if (grey[idx].load(std::memory_order_relaxed)) continue;
                const glm::dvec3 blo = glm::dvec3(i, j, k) / double(n) - pad,
                                 bhi = glm::dvec3(i + 1, j + 1, k + 1) / double(n) + pad;
                if (triangle_overlaps_box(a, b, c, blo, bhi))
                  grey[idx].store(1, std::memory_order_relaxed);
              }
        }
      },
      256);
  stats.degenerate_triangles = degenerate.load();
  cells.assign(count, {});
  std::vector<int8_t> state(count, -1);  // -1 undecided
  for (size_t i = 0; i < count; ++i)
    if (grey[i].load()) state[i] = int8_t(CellState::Grey);
  auto neighbours = [n](size_t idx, auto&& visit) {
    const int i = int(idx % n), j = int((idx / n) % n), k = int(idx / (size_t(n) * n));
    const int d[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
    for (const auto& o : d) {
      const int a = i + o[0], b = j + o[1], c = k + o[2];
      if (a < 0 || b < 0 || c < 0 || a >= n || b >= n || c >= n) continue;
      visit((size_t(c) * n + b) * n + a);
    }
  };
  auto fill = [&](size_t seed, int8_t value) {
    std::deque<size_t> queue{seed};
    state[seed] = value;
    while (!queue.empty()) {
      const size_t c = queue.front();
      queue.pop_front();
      neighbours(c, [&](size_t nb) {
        if (state[nb] != -1) return;
        state[nb] = value;
        queue.push_back(nb);
      });
    }
  };
  // The outside: non-grey cells on the grid's border and everything they reach.
  for (size_t idx = 0; idx < count; ++idx) {
    const int i = int(idx % n), j = int((idx / n) % n), k = int(idx / (size_t(n) * n));
    const bool border = i == 0 || j == 0 || k == 0 || i == n - 1 || j == n - 1 || k == n - 1;
    if (border && state[idx] == -1) fill(idx, int8_t(CellState::White));
  }
  // Enclosed regions: inside or outside by parity from one cell's centre.
  for (size_t idx = 0; idx < count; ++idx) {
    if (state[idx] != -1) continue;
    const int i = int(idx % n), j = int((idx / n) % n), k = int(idx / (size_t(n) * n));
    bool agreed = true;
    const bool inside = parity_inside(scene, (glm::dvec3(i, j, k) + 0.5) / double(n), &agreed);
    if (!agreed) ++stats.ambiguous_regions;
    fill(idx, int8_t(inside ? CellState::Black : CellState::White));
  }
  for (size_t idx = 0; idx < count; ++idx) cells[idx].state = CellState(state[idx]);
}

// Texels whose line misses the surface have no normal or colour of their own; bilinear reads
// at the edge of a face's surface would blend in a made-up one (a bright rim of "up" normals
// along cell borders). They take their nearest sampled neighbours', grown ring by ring (the
// usual dilation of texture atlases).
void dilate_attributes(const std::vector<uint8_t>& crossings, int res,
                       std::vector<glm::vec3>& normal, std::vector<glm::vec3>& color) {
  const size_t texels = size_t(res) * res, faces = crossings.size() / texels;
  parallel_for(
      faces,
      [&](size_t begin, size_t end) {
        std::vector<uint8_t> known(texels), next(texels);
        for (size_t f = begin; f < end; ++f) {
          const size_t base = f * texels;
          for (size_t t = 0; t < texels; ++t) known[t] = crossings[base + t] > 0;
          for (bool grew = true; grew;) {
            grew = false;
            next = known;
            for (int y = 0; y < res; ++y)
              for (int x = 0; x < res; ++x) {
                const size_t t = size_t(y) * res + x;
                if (known[t]) continue;
                glm::vec3 n(0), c(0);
                int count = 0;
                for (int dy = -1; dy <= 1; ++dy)
                  for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= res || ny >= res) continue;
                    const size_t u = size_t(ny) * res + nx;
                    if (!known[u]) continue;
                    n += normal[base + u];
                    c += color[base + u];
                    ++count;
                  }
                if (count == 0) continue;
                normal[base + t] = glm::length(n) > 0 ? glm::normalize(n) : normal[base + t];
                color[base + t] = c / float(count);
                next[t] = 1;
                grew = true;
              }
            known.swap(next);
          }
        }
      },
      1);
}

}  // namespace

// The construction's stages (Section 3.3), each on the complex it fills.
struct CellComplexBuilder {
  static void check_options(const CellComplexOptions& options) {
    if (options.grid > 0 && options.grid > kMaxCellGrid)
      throw ConfigError("cell grid " + std::to_string(options.grid) + " is above the cap " +
                        std::to_string(kMaxCellGrid));
    if (options.resolution < 2 || options.resolution > 1024)
      throw ConfigError("cell map resolution must be 2 to 1024, got " +
                        std::to_string(options.resolution));
    if (options.distance_bits != 8 && options.distance_bits != 16)
      throw ConfigError("distance_bits must be 8 or 16");
  }

  // Section 3.3.3: start at 1 and double until the occluded-fragment ratio is below the
  // threshold or N_max is reached.
  static CellComplex search_grid(const TriangleMesh& mesh, const CellComplexOptions& options) {
    std::vector<GridTrial> trials;
    double total_ms = 0;
    const int cap = std::clamp(options.grid_max, 1, kMaxCellGrid);
    for (int n = 1;; n *= 2) {
      CellComplexOptions o = options;
      o.grid = std::min(n, cap);
      CellComplex c = CellComplex::build(mesh, o);
      trials.push_back({o.grid, c.stats_.occluded_ratio(), c.stats_.grey_cells,
                        c.stats_.domain_faces, c.stats_.construction_ms});
      total_ms += c.stats_.construction_ms;
      if (c.stats_.occluded_ratio() < options.threshold || o.grid >= cap) {
        c.stats_.trials = trials;
        c.stats_.construction_ms = total_ms;
        return c;
      }
    }
  }

  // Each grey cell's internal faces, configuration (case and projection) and domain faces.
  static void configure_cells(CellComplex& cc) {
    const int n = cc.n_;
    CellComplex::Stats& st = cc.stats_;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          CellComplex::Cell& c = cc.cells_[cc.index(i, j, k)];
          if (c.state == CellState::White) ++st.white_cells;
          if (c.state == CellState::Black) ++st.black_cells;
          if (c.state != CellState::Grey) continue;
          ++st.grey_cells;
          uint8_t internal = 0;
          for (int f = 0; f < 6; ++f) {
            int nb[3] = {i, j, k};
            nb[f / 2] += f % 2 ? 1 : -1;
            const bool outside = nb[f / 2] < 0 || nb[f / 2] >= n;
            if (!outside && cc.cells_[cc.index(nb[0], nb[1], nb[2])].state != CellState::White)
              internal |= uint8_t(1u << f);
          }
          c.internal_mask = internal;
          c.config = configure_cell(internal);
          ++st.cases[int(c.config.base_case)];
          (internal == 63 ? st.interior_grey : st.border_grey)++;
          c.first_face = int(cc.faces_.size());
          for (int f = 0; f < 6; ++f)
            if ((c.config.domain_mask >> f) & 1u) cc.faces_.push_back({int(cc.index(i, j, k)), f});
        }
    st.domain_faces = long(cc.faces_.size());
  }

  // Crossings of one texel's projection line, and the fragments they count.
  struct TexelCount {
    long fragments = 0, occluded = 0, multi = 0;
  };

  // One texel of one domain face (Section 3.3.2): a ray along its projection line (exact per
  // texel) gives the first crossing's distance, normal and colour.
  static void sample_texel(CellComplex& cc, RTCScene scene, const TriangleMesh& mesh, size_t t,
                           TexelCount& count) {
    const int n = cc.n_, res = cc.res_;
    const size_t texels = size_t(res) * res;
    const CellComplex::DomainFace& df = cc.faces_[t / texels];
    const int x = int((t % texels) % res), y = int((t % texels) / res);
    const CellComplex::Cell& c = cc.cells_[df.cell];
    const glm::dvec3 cell0(df.cell % n, (df.cell / n) % n, df.cell / (size_t(n) * n));
    const CellLine line =
        face_line(c.config.projection, df.face, {(x + 0.5) / res, (y + 0.5) / res});
    const glm::dvec3 from = (cell0 + line.on_face) / double(n);
    const glm::dvec3 to = (cell0 + line.inner) / double(n);
    const double length = glm::length(to - from);
    // The face point is outside on an external face (it touches a white cell); on an interior
    // grey cell's face it is inside next to a black cell, else by parity.
    bool face_inside = false;
    if (c.internal_mask == 63) {
      int nb[3] = {int(cell0.x), int(cell0.y), int(cell0.z)};
      nb[df.face / 2] += df.face % 2 ? 1 : -1;
      const bool in_grid = nb[df.face / 2] >= 0 && nb[df.face / 2] < n;
      const CellState s =
          in_grid ? cc.cells_[cc.index(nb[0], nb[1], nb[2])].state : CellState::White;
      face_inside =
          s == CellState::Black || (s == CellState::Grey && parity_inside(scene, from, nullptr));
    }
    double d = 1;  // outside all along
    int hits = 0;
    if (length > 0) {
      RTCRayHit first{};
      hits = count_crossings(scene, from, (to - from) / length, length, &first);
      count.fragments += hits;
      count.occluded += std::max(0, hits - 1);
      count.multi += hits > 1;
      if (hits > 0) {
        d = std::clamp(double(first.ray.tfar) / length, 0.0, 1.0);
        const glm::dvec3 ng(first.hit.Ng_x, first.hit.Ng_y, first.hit.Ng_z);
        if (glm::dot(ng, ng) > 0) cc.normal_[t] = glm::vec3(glm::normalize(ng));
        if (!mesh.triangle_colors.empty()) cc.color_[t] = mesh.triangle_colors[first.hit.primID];
      }
    }
    // A line inside all along is stored as entering at its face point (d = 0, no flag), so it
    // interpolates continuously with its neighbours that enter just after theirs; the flag
    // marks only lines that start inside and leave (inside up to d).
    if (face_inside && hits == 0) d = 0;
    cc.face_inside_[t] = face_inside && hits > 0;
    cc.crossings_[t] = uint8_t(std::min(hits, 255));
    cc.distance_[t] = uint16_t(std::lround(d * cc.distance_scale()));
  }

  // Sampling (Section 3.3.2) of every texel of every domain face; every crossing counted as a
  // fragment.
  static void sample_faces(CellComplex& cc, RTCScene scene, const TriangleMesh& mesh) {
    const size_t texels = size_t(cc.res_) * cc.res_;
    const size_t all = cc.faces_.size() * texels;
    cc.distance_.assign(all, 0);
    cc.face_inside_.assign(all, 0);
    cc.crossings_.assign(all, 0);
    cc.normal_.assign(all, glm::vec3(0, 0, -1));
    cc.color_.assign(all, kCellAlbedo);
    std::atomic<long> fragments{0}, occluded{0}, multi{0};
    parallel_for(
        all,
        [&](size_t begin, size_t end) {
          TexelCount count;
          for (size_t t = begin; t < end; ++t) sample_texel(cc, scene, mesh, t, count);
          fragments += count.fragments;
          occluded += count.occluded;
          multi += count.multi;
        },
        1024);
    dilate_attributes(cc.crossings_, cc.res_, cc.normal_, cc.color_);
    cc.stats_.fragments = fragments.load();
    cc.stats_.occluded_fragments = occluded.load();
    cc.stats_.multi_crossing_texels = multi.load();
  }
};

CellComplex CellComplex::build(const TriangleMesh& mesh, const CellComplexOptions& options) {
  CellComplexBuilder::check_options(options);
  if (options.grid <= 0) return CellComplexBuilder::search_grid(mesh, options);
  CellComplex cc;
  cc.n_ = options.grid;
  cc.res_ = options.resolution;
  cc.bits_ = options.distance_bits;
  EmbreeScene embree(mesh);
  Stats& st = cc.stats_;
  st.mesh_triangles = long(mesh.triangles.size());
  cc.mesh_ = mesh;

  auto t0 = std::chrono::steady_clock::now();
  classify(mesh, embree.scene, cc.n_, cc.cells_, st);
  CellComplexBuilder::configure_cells(cc);
  st.classify_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  CellComplexBuilder::sample_faces(cc, embree.scene, mesh);
  st.sample_ms = ms_since(t0);
  st.construction_ms = st.classify_ms + st.sample_ms;
  return cc;
}

CellComplex CellComplex::with_sampled_maps(const std::vector<float>& distance,
                                           const std::vector<glm::vec3>& normal) const {
  if (distance.size() != distance_.size() || normal.size() != distance_.size())
    throw std::invalid_argument(
        "CellComplex::with_sampled_maps: the maps are not the complex's size");
  CellComplex out = *this;
  std::vector<uint8_t> found(distance.size());
  for (size_t t = 0; t < distance.size(); ++t) {
    found[t] = distance[t] < 1.0f;
    if (found[t]) {
      out.distance_[t] = uint16_t(std::lround(double(distance[t]) * distance_scale()));
      out.normal_[t] = normal[t];
    } else if (crossings_[t] > 0) {
      out.distance_[t] = uint16_t(std::lround(distance_scale()));  // the CPU's point, not found
    }
  }
  std::vector<glm::vec3> color = color_;  // dilated already; only the normals are new
  dilate_attributes(found, res_, out.normal_, color);
  return out;
}

size_t CellComplex::gpu_bytes() const {
  const size_t texels = faces_.size() * size_t(res_) * res_;
  // Distance + inside flag (2 x 16 or 2 x 8 bits), normal and colour RGBA8, the cell table.
  return texels * (bits_ == 16 ? 4 : 2) + texels * 4 * 2 + size_t(n_) * n_ * n_ * 8;
}

CellComplex::Lookup CellComplex::lookup(const glm::dvec3& p) const {
  Lookup l;
  const glm::dvec3 g = p * double(n_);
  glm::ivec3 c;
  for (int k = 0; k < 3; ++k) {
    if (!(g[k] >= 0 && g[k] <= n_)) return l;
    c[k] = std::min(int(std::floor(g[k])), n_ - 1);
  }
  const Cell& cell = cells_[index(c.x, c.y, c.z)];
  if (cell.state != CellState::Grey) return l;
  l.line = project_in_cell(cell.config.projection, cell.config.domain_mask, g - glm::dvec3(c));
  const unsigned mask = cell.config.domain_mask;
  if (l.line.face < 0 || !((mask >> l.line.face) & 1u)) return l;
  l.face_index = cell.first_face + popcount6(mask & ((1u << l.line.face) - 1u));
  l.st = face_coords(l.line.face, l.line.on_face);
  return l;
}

double CellComplex::sample_distance(int face_index, glm::dvec2 st, bool* inside_flag) const {
  const Bilinear b = bilinear(st, res_);
  const size_t base = size_t(face_index) * res_ * res_;
  auto at = [&](int x, int y) { return base + size_t(y) * res_ + x; };
  auto lerp2 = [&](auto value) {
    const double top = value(at(b.x0, b.y0)) * (1 - b.fx) + value(at(b.x1, b.y0)) * b.fx;
    const double bottom = value(at(b.x0, b.y1)) * (1 - b.fx) + value(at(b.x1, b.y1)) * b.fx;
    return top * (1 - b.fy) + bottom * b.fy;
  };
  if (inside_flag) *inside_flag = lerp2([&](size_t i) { return double(face_inside_[i]); }) > 0.5;
  return lerp2([&](size_t i) { return double(distance_[i]); }) / distance_scale();
}

namespace {

glm::dvec3 bilinear_vec3(const std::vector<glm::vec3>& texels, size_t base, int res,
                         glm::dvec2 st) {
  const Bilinear b = bilinear(st, res);
  auto at = [&](int x, int y) { return glm::dvec3(texels[base + size_t(y) * res + x]); };
  return (at(b.x0, b.y0) * (1 - b.fx) + at(b.x1, b.y0) * b.fx) * (1 - b.fy) +
         (at(b.x0, b.y1) * (1 - b.fx) + at(b.x1, b.y1) * b.fx) * b.fy;
}

}  // namespace

glm::dvec3 CellComplex::sample_normal(int face_index, glm::dvec2 st) const {
  const glm::dvec3 n = bilinear_vec3(normal_, size_t(face_index) * res_ * res_, res_, st);
  const double len = glm::length(n);
  return len > 0 ? n / len : glm::dvec3(0, 0, -1);
}

glm::dvec3 CellComplex::sample_color(int face_index, glm::dvec2 st) const {
  return bilinear_vec3(color_, size_t(face_index) * res_ * res_, res_, st);
}

bool CellComplex::encoded_inside(const glm::dvec3& p) const {
  const glm::dvec3 g = p * double(n_);
  for (int k = 0; k < 3; ++k)
    if (!(g[k] >= 0 && g[k] <= n_)) return false;
  const glm::ivec3 c = glm::min(glm::ivec3(glm::floor(g)), glm::ivec3(n_ - 1));
  const CellState s = cells_[index(c.x, c.y, c.z)].state;
  if (s != CellState::Grey) return s == CellState::Black;
  const Lookup l = lookup(p);
  if (l.face_index < 0) return false;
  bool flag = false;
  const double d = sample_distance(l.face_index, l.st, &flag);
  return flag != (l.line.along > d * l.line.length);
}

}  // namespace rl
