// Meshes around a cell complex: the cube frame a mesh is encoded in, midpoint subdivision, and
// the geometry-based rendering's mesh reconstructed from the domain faces' texels (Section
// 3.5.1: one vertex per texel, unprojected along its projection line).
#include <algorithm>
#include <cmath>

#include "relief/cell_complex.h"

namespace rl {

BakeFrame cell_frame(const TriangleMesh& mesh, int up, double margin) {
  // The bake's frame (axes, footprint), made a cube about the mesh's centre.
  BakeFrame f = bake_frame(mesh, up, margin);
  const glm::dvec3 extent = mesh.hi - mesh.lo;
  f.side = f.height = std::max({extent.x, extent.y, extent.z, 1e-9}) * (1 + 2 * margin);
  const glm::dvec3 centre = 0.5 * (mesh.lo + mesh.hi);
  f.origin = centre - glm::dvec3(0.5 * f.side);
  f.origin[up] = centre[up] + 0.5 * f.side;
  return f;
}

TriangleMesh to_frame(const TriangleMesh& mesh, const BakeFrame& frame) {
  TriangleMesh out = mesh;
  out.lo = glm::dvec3(std::numeric_limits<double>::max());
  out.hi = -out.lo;
  for (glm::vec3& p : out.positions) {
    const glm::dvec3 t = frame.texture_from_mesh(glm::dvec3(p));
    p = glm::vec3(t);
    out.lo = glm::min(out.lo, t);
    out.hi = glm::max(out.hi, t);
  }
  return out;
}

TriangleMesh subdivide_midpoints(const TriangleMesh& mesh, int times) {
  TriangleMesh m = mesh;
  for (int k = 0; k < times; ++k) {
    std::vector<glm::uvec3> tris;
    std::vector<glm::vec3> colors;
    tris.reserve(m.triangles.size() * 4);
    for (size_t i = 0; i < m.triangles.size(); ++i) {
      const glm::uvec3 t = m.triangles[i];
      const unsigned base = unsigned(m.positions.size());
      m.positions.push_back(0.5f * (m.positions[t.x] + m.positions[t.y]));
      m.positions.push_back(0.5f * (m.positions[t.y] + m.positions[t.z]));
      m.positions.push_back(0.5f * (m.positions[t.z] + m.positions[t.x]));
      if (!m.uvs.empty()) {
        m.uvs.push_back(0.5f * (m.uvs[t.x] + m.uvs[t.y]));
        m.uvs.push_back(0.5f * (m.uvs[t.y] + m.uvs[t.z]));
        m.uvs.push_back(0.5f * (m.uvs[t.z] + m.uvs[t.x]));
      }
      const unsigned ab = base, bc = base + 1, ca = base + 2;
      for (glm::uvec3 c : {glm::uvec3(t.x, ab, ca), glm::uvec3(ab, t.y, bc),
                           glm::uvec3(ca, bc, t.z), glm::uvec3(ab, bc, ca)}) {
        tris.push_back(c);
        if (!m.triangle_colors.empty()) colors.push_back(m.triangle_colors[i]);
      }
    }
    m.triangles = std::move(tris);
    if (!m.triangle_colors.empty()) m.triangle_colors = std::move(colors);
  }
  return m;
}

namespace {

// One texel of a face's mip level: the mean distance, normal and colour of the block's lines
// that meet the surface, valid where at least half of them do.
struct MipTexel {
  bool valid = false;
  double d = 0;
  glm::dvec3 normal{0}, color{0};
};

// Domain face fi's texels averaged over blocks of block x block, coarse x coarse of them.
void face_mip(const CellComplex& cc, size_t fi, int block, int coarse, std::vector<MipTexel>& mip) {
  const int res = cc.resolution();
  const size_t base = fi * size_t(res) * res;
  for (int y = 0; y < coarse; ++y)
    for (int x = 0; x < coarse; ++x) {
      MipTexel& tx = mip[size_t(y) * coarse + x];
      tx = MipTexel{};
      int hits = 0;
      for (int by = 0; by < block; ++by)
        for (int bx = 0; bx < block; ++bx) {
          const size_t t = base + size_t(y * block + by) * res + (x * block + bx);
          if (cc.crossings()[t] == 0) continue;
          ++hits;
          tx.d += cc.distance()[t] / cc.distance_scale();
          tx.normal += glm::dvec3(cc.normal()[t]);
          tx.color += glm::dvec3(cc.color()[t]);
        }
      tx.valid = 2 * hits >= block * block;
      if (hits == 0) continue;
      tx.d /= hits;
      tx.color /= double(hits);
    }
}

// Vertices at the texels' corners, so a face's triangles reach its edges (where its
// neighbours' begin): each the mean of the valid texels around it, if they all are; -1 where
// not. Appended to m; vertex holds their indices, (coarse + 1)^2 of them.
void corner_vertices(const CellComplex& cc, const CellComplex::DomainFace& df, int coarse,
                     const std::vector<MipTexel>& mip, CellMesh& m, std::vector<int>& vertex) {
  const int n = cc.grid();
  const CellComplex::Cell& cell = cc.cells()[df.cell];
  const glm::dvec3 cell0(df.cell % n, (df.cell / n) % n, df.cell / (size_t(n) * n));
  for (int y = 0; y <= coarse; ++y)
    for (int x = 0; x <= coarse; ++x) {
      int& v = vertex[size_t(y) * (coarse + 1) + x];
      v = -1;
      MipTexel sum;
      int count = 0;
      bool valid = true;
      for (int ty = std::max(0, y - 1); ty <= std::min(coarse - 1, y); ++ty)
        for (int tx = std::max(0, x - 1); tx <= std::min(coarse - 1, x); ++tx) {
          const MipTexel& t = mip[size_t(ty) * coarse + tx];
          valid &= t.valid;
          sum.d += t.d;
          sum.normal += t.normal;
          sum.color += t.color;
          ++count;
        }
      if (!valid) continue;
      const CellLine line =
          face_line(cell.config.projection, df.face, {double(x) / coarse, double(y) / coarse});
      const glm::dvec3 q = line.on_face + (line.inner - line.on_face) * (sum.d / count);
      v = int(m.position.size());
      m.position.push_back(glm::vec3((cell0 + q) / double(n)));
      const double len = glm::length(sum.normal);
      m.normal.push_back(glm::vec3(len > 0 ? sum.normal / len : glm::dvec3(0, 0, -1)));
      m.color.push_back(glm::vec3(sum.color / double(count)));
    }
}

// Two triangles per texel whose four corners have vertices, each kept only if its edges are
// short: a long edge joins two sheets across a depth discontinuity, not the surface.
void face_triangles(const std::vector<int>& vertex, int coarse, double limit, CellMesh& m) {
  const int w = coarse + 1;
  auto short_edges = [&](int i, int j, int k) {
    const glm::vec3 &p = m.position[i], &q = m.position[j], &r = m.position[k];
    return glm::length(p - q) <= limit && glm::length(q - r) <= limit &&
           glm::length(r - p) <= limit;
  };
  for (int y = 0; y < coarse; ++y)
    for (int x = 0; x < coarse; ++x) {
      const int a = vertex[size_t(y) * w + x], b = vertex[size_t(y) * w + x + 1],
                c = vertex[size_t(y + 1) * w + x + 1], e = vertex[size_t(y + 1) * w + x];
      if (a < 0 || b < 0 || c < 0 || e < 0) continue;
      if (short_edges(a, b, c)) m.triangles.push_back(glm::uvec3(a, b, c));
      if (short_edges(a, c, e)) m.triangles.push_back(glm::uvec3(a, c, e));
    }
}

}  // namespace

CellMesh reconstruct_cell_mesh(const CellComplex& cc, int lod, double max_edge_texels) {
  CellMesh m;
  const int res = cc.resolution(), n = cc.grid();
  const int block = std::min(1 << std::max(0, lod), res), coarse = res / block;
  const double limit = max_edge_texels / (double(coarse) * n);
  std::vector<MipTexel> mip(size_t(coarse) * coarse);
  std::vector<int> vertex(size_t(coarse + 1) * (coarse + 1));
  for (size_t fi = 0; fi < cc.domain_faces().size(); ++fi) {
    face_mip(cc, fi, block, coarse, mip);
    corner_vertices(cc, cc.domain_faces()[fi], coarse, mip, m, vertex);
    face_triangles(vertex, coarse, limit, m);
  }
  return m;
}

}  // namespace rl
