#include "relief/cell_projection_bend.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "core/columns.h"

namespace rl {

namespace {

// The sweep writes them beside the cell complex's columns, per projection type.
const ColumnDeclaration projection_bend_columns = [] {
  std::vector<ColumnSpec> specs;
  for (const char* type : {"perspective", "axial", "planar", "parallel"}) {
    const std::string name = type;
    specs.push_back(ColumnSpec{
        "edge_pieces_" + name, "pieces",
        "mesh edge pieces inside " + name + " cells projected onto one domain face (Figure 3)"}
                        .neither_better());
    specs.push_back(ColumnSpec{"edge_bend_" + name + "_texels_max", "texels",
                               "their largest bend: distance of the projected piece from the "
                               "chord between its projected ends, in face texels"}
                        .neither_better());
    specs.push_back(ColumnSpec{"edge_bend_" + name + "_texels_mean", "texels", "their mean bend"}
                        .neither_better());
  }
  return ColumnDeclaration("relief (cell complex)", specs);
}();

// The parameters in (0, 1) where a + t (b - a) crosses a cell boundary of an n-cell grid.
std::vector<double> cell_crossings(const glm::dvec3& a, const glm::dvec3& b, int n) {
  std::vector<double> ts = {0.0, 1.0};
  for (int axis = 0; axis < 3; ++axis) {
    const double lo = std::min(a[axis], b[axis]) * n, hi = std::max(a[axis], b[axis]) * n;
    if (hi - lo < 1e-12) continue;
    for (double k = std::floor(lo) + 1; k < hi; k += 1)
      ts.push_back((k / n - a[axis]) / (b[axis] - a[axis]));
  }
  std::sort(ts.begin(), ts.end());
  return ts;
}

// Distance of p from the segment s0 -> s1.
double to_segment(const glm::dvec2& p, const glm::dvec2& s0, const glm::dvec2& s1) {
  const glm::dvec2 d = s1 - s0;
  const double len2 = glm::dot(d, d);
  const double u = len2 > 0 ? std::clamp(glm::dot(p - s0, d) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (s0 + u * d));
}

// The bend of the piece p0 -> p1 (cell-local) in its cell, in face texels; negative when the
// piece does not project onto one face.
double piece_bend(const CellComplex::Cell& cell, const glm::dvec3& p0, const glm::dvec3& p1,
                  int samples, int resolution) {
  std::vector<glm::dvec2> st;
  int face = -2;
  for (int k = 0; k <= samples + 1; ++k) {
    const CellLine l = project_in_cell(cell.config.projection, cell.config.domain_mask,
                                       p0 + (p1 - p0) * (double(k) / (samples + 1)));
    if (face != -2 && l.face != face) return -1;
    face = l.face;
    st.push_back(face_coords(face, l.on_face));
  }
  double bend = 0;
  for (const glm::dvec2& p : st) bend = std::max(bend, to_segment(p, st.front(), st.back()));
  return bend * resolution;
}

}  // namespace

ProjectionBend projection_bend(const CellComplex& cc, int samples) {
  ProjectionBend out;
  const TriangleMesh& mesh = cc.mesh();
  const int n = cc.grid();
  std::set<std::pair<uint32_t, uint32_t>> edges;
  for (const glm::uvec3& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
  std::array<double, 4> sum{};
  for (const auto& [i, j] : edges) {
    const glm::dvec3 a(mesh.positions[i]), b(mesh.positions[j]);
    const std::vector<double> ts = cell_crossings(a, b, n);
    for (size_t k = 0; k + 1 < ts.size(); ++k) {
      if (ts[k + 1] - ts[k] < 1e-9) continue;
      const glm::dvec3 mid = a + (b - a) * (0.5 * (ts[k] + ts[k + 1]));
      const glm::ivec3 c = glm::clamp(glm::ivec3(glm::floor(mid * double(n))), 0, n - 1);
      const CellComplex::Cell& cell = cc.cell(c.x, c.y, c.z);
      if (cell.state != CellState::Grey) continue;
      const glm::dvec3 origin = glm::dvec3(c);
      const double bend =
          piece_bend(cell, (a + (b - a) * ts[k]) * double(n) - origin,
                     (a + (b - a) * ts[k + 1]) * double(n) - origin, samples, cc.resolution());
      if (bend < 0) continue;
      const size_t type = size_t(cell.config.projection.type);
      ++out.pieces[type];
      sum[type] += bend;
      out.max_texels[type] = std::max(out.max_texels[type], bend);
    }
  }
  for (size_t type = 0; type < 4; ++type)
    out.mean_texels[type] = out.pieces[type] ? sum[type] / double(out.pieces[type]) : 0.0;
  return out;
}

}  // namespace rl
