// Relief mapping on cubic cell complexes (Apaza & Andujar, Section 3): the 64 face
// configurations and their projections, classification and sampling on analytic meshes, the
// encoded surface against the mesh, and the hard cases of construction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "relief/cell_complex.h"
#include "relief/cell_projection_bend.h"
#include "support/test_support.h"

namespace rl {
namespace {

// The 24 rotations of the cube as signed permutation matrices of determinant +1.
std::vector<glm::dmat3> cube_rotations() {
  std::vector<glm::dmat3> out;
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& p : perms)
    for (int signs = 0; signs < 8; ++signs) {
      glm::dmat3 m(0.0);
      for (int r = 0; r < 3; ++r) m[p[r]][r] = (signs >> r) & 1 ? -1.0 : 1.0;  // column p[r]
      if (glm::determinant(m) > 0) out.push_back(m);
    }
  return out;
}

int face_of_normal(const glm::dvec3& n) {
  for (int a = 0; a < 3; ++a)
    if (std::abs(n[a]) > 0.5) return 2 * a + (n[a] > 0 ? 1 : 0);
  return -1;
}

uint8_t rotate_mask(const glm::dmat3& r, uint8_t mask) {
  uint8_t out = 0;
  for (int f = 0; f < 6; ++f) {
    if (!((mask >> f) & 1u)) continue;
    glm::dvec3 n(0);
    n[f / 2] = f % 2 ? 1 : -1;
    out |= uint8_t(1u << face_of_normal(r * n));
  }
  return out;
}

TEST(CellConfigurations, AllSixtyFourReduceToTheTenBaseCasesUnderRotation) {
  // Section 3.2: 2^6 internal/external configurations, ten classes under the cube's rotations.
  // Orbit sizes: 1 + 6 + 12 + 3 + 12 + 8 + 3 + 12 + 6 + 1 = 64.
  const std::vector<glm::dmat3> rotations = cube_rotations();
  ASSERT_EQ(rotations.size(), 24u);
  std::array<int, 10> count{};
  std::vector<std::vector<uint8_t>> orbits(10);
  for (int mask = 0; mask < 64; ++mask) {
    const CellCase c = configure_cell(uint8_t(mask)).base_case;
    ++count[int(c)];
    // A rotated configuration is the same base case...
    for (const glm::dmat3& r : rotations)
      EXPECT_EQ(configure_cell(rotate_mask(r, uint8_t(mask))).base_case, c) << "mask " << mask;
    orbits[int(c)].push_back(uint8_t(mask));
  }
  const std::array<int, 10> expected = {1, 6, 12, 3, 12, 8, 3, 12, 6, 1};
  EXPECT_EQ(count, expected);
  // ... and every configuration of a case is a rotation of its first (one orbit per case).
  for (int c = 0; c < 10; ++c) {
    std::set<uint8_t> orbit;
    for (const glm::dmat3& r : rotations) orbit.insert(rotate_mask(r, orbits[c][0]));
    EXPECT_EQ(orbit.size(), orbits[c].size()) << cell_case_name(CellCase(c));
    for (uint8_t m : orbits[c]) EXPECT_TRUE(orbit.count(m)) << cell_case_name(CellCase(c));
  }
}

TEST(CellConfigurations, ProjectionTypesAreTheFourOfSection32) {
  using T = CellProjection::Type;
  const std::map<CellCase, T> expected = {
      {CellCase::C0, T::Perspective},  {CellCase::C1, T::Perspective},
      {CellCase::C2a, T::Perspective}, {CellCase::C2b, T::Axial},
      {CellCase::C3a, T::Axial},       {CellCase::C3b, T::Perspective},
      {CellCase::C4a, T::Planar},      {CellCase::C4b, T::Axial},
      {CellCase::C5, T::Parallel},     {CellCase::C6, T::Perspective}};
  for (int mask = 0; mask < 64; ++mask) {
    const CellConfiguration c = configure_cell(uint8_t(mask));
    EXPECT_EQ(c.projection.type, expected.at(c.base_case)) << "mask " << mask;
    // Domain faces: the external ones, or all six for an interior grey cell.
    EXPECT_EQ(c.domain_mask, mask == 63 ? 63 : (~mask & 63)) << "mask " << mask;
  }
}

TEST(CellConfigurations, EveryPointProjectsOntoADomainFaceAlongOneLine) {
  // The property Section 3.2 chooses each parameter for: points inside the cell project only
  // onto its domain faces. Also: the line through q runs from its face point through q to its
  // inner end (centre, axis, plane or far face), and points further in project to the same
  // face point -- the lines do not cross, so one distance per texel is well defined. A wrong
  // centre (e.g. the cell's centre for case 1) sends points to an internal face and fails.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int mask = 0; mask < 64; ++mask) {
    const CellConfiguration c = configure_cell(uint8_t(mask));
    SCOPED_TRACE("mask " + std::to_string(mask) + " case " + cell_case_name(c.base_case));
    int checked = 0;
    for (int i = 0; i < 400; ++i) {
      glm::dvec3 q(u01(rng), u01(rng), u01(rng));
      if (i < 8) q = glm::dvec3(i & 1, (i >> 1) & 1, (i >> 2) & 1) * 0.98 + 0.01;  // corners
      const CellLine l = project_in_cell(c.projection, c.domain_mask, q);
      ASSERT_GE(l.face, 0);
      ASSERT_TRUE((c.domain_mask >> l.face) & 1u) << "face " << l.face;
      EXPECT_NEAR(l.on_face[l.face / 2], l.face % 2, 1e-12);
      EXPECT_LE(l.along, l.length + 1e-9);
      // q lies on the segment between the face point and the inner end.
      EXPECT_NEAR(glm::length(l.on_face - q) + glm::length(q - l.inner), l.length, 1e-9);
      // A point further in along the line maps back to the same face point.
      const glm::dvec3 deeper = q + 0.5 * (l.inner - q);
      if (glm::length(deeper - l.inner) > 1e-6) {
        const CellLine l2 = project_in_cell(c.projection, c.domain_mask, deeper);
        EXPECT_EQ(l2.face, l.face);
        EXPECT_LT(glm::length(l2.on_face - l.on_face), 1e-9);
        ++checked;
      }
      // The texel's line (face_line) from that face point is the same line.
      const CellLine fl = face_line(c.projection, l.face, face_coords(l.face, l.on_face));
      EXPECT_NEAR(fl.length, l.length, 1e-9);
      EXPECT_LT(glm::length(fl.inner - l.inner), 1e-9);
    }
    EXPECT_GT(checked, 300);
  }
}

// A closed hexagonal tube along x (radius `r` about y = z = 0.5, from x0 to x1), its sides
// one quad each, split along a diagonal that winds a sixth of a turn along the whole tube.
TriangleMesh hexagonal_tube(double r, double x0, double x1) {
  TriangleMesh m;
  for (double x : {x0, x1})
    for (int k = 0; k < 6; ++k) {
      const double a = k * 3.14159265358979 / 3;
      m.positions.emplace_back(x, 0.5 + r * std::cos(a), 0.5 + r * std::sin(a));
    }
  m.positions.emplace_back(x0, 0.5, 0.5);
  m.positions.emplace_back(x1, 0.5, 0.5);
  for (uint32_t k = 0; k < 6; ++k) {
    const uint32_t k1 = (k + 1) % 6;
    m.triangles.emplace_back(k, k1, 6 + k1);
    m.triangles.emplace_back(k, 6 + k1, 6 + k);
    m.triangles.emplace_back(12, k1, k);          // cap at x0
    m.triangles.emplace_back(13, 6 + k, 6 + k1);  // cap at x1
  }
  return m;
}

TEST(CellProjectionBend, TheAxialProjectionAloneBendsStraightEdges) {
  // Apaza & Andujar, Figure 3. The tube runs through the middle row of a 3^3 grid: its middle
  // cell (internal faces -x and +x, case 2b) projects axially about x, its end cells (one
  // internal face, case 1) perspectively. Pieces of the winding diagonals bend on the middle
  // cell's faces; every piece in the end cells stays straight to rounding.
  const CellComplex cc =
      CellComplex::build(hexagonal_tube(0.12, 0.02, 0.98), {.grid = 3, .resolution = 64});
  ASSERT_EQ(cc.cell(1, 1, 1).config.projection.type, CellProjection::Type::Axial);
  ASSERT_EQ(cc.cell(0, 1, 1).config.projection.type, CellProjection::Type::Perspective);
  const ProjectionBend bend = projection_bend(cc);
  const size_t axial = size_t(CellProjection::Type::Axial);
  const size_t perspective = size_t(CellProjection::Type::Perspective);
  std::printf("hexagonal tube: %ld axial pieces, bend up to %.3g texels; %ld perspective, %.3g\n",
              bend.pieces[axial], bend.max_texels[axial], bend.pieces[perspective],
              bend.max_texels[perspective]);
  EXPECT_GT(bend.pieces[axial], 6);
  EXPECT_GT(bend.max_texels[axial], 0.1);
  EXPECT_GT(bend.pieces[perspective], 12);
  EXPECT_LT(bend.max_texels[perspective], 1e-9);
}

TEST(CellComplexBuild, ClassifiesASphereLikeItsDistanceField) {
  const glm::dvec3 centre(0.5, 0.5, 0.5);
  const double r = 0.37;
  const TriangleMesh sphere = test::uv_sphere(centre, r, 96, 48);
  for (int n : {1, 2, 4, 8}) {
    SCOPED_TRACE("N " + std::to_string(n));
    const CellComplex cc = CellComplex::build(sphere, {.grid = n, .resolution = 16});
    const double half_diag = std::sqrt(3.0) / (2 * n), facet = 2e-3;  // tessellation sag
    long grey = 0;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const double d = glm::length((glm::dvec3(i, j, k) + 0.5) / double(n) - centre);
          const CellState s = cc.cell(i, j, k).state;
          if (d < r - half_diag - facet) {
            EXPECT_EQ(s, CellState::Black) << i << j << k;
          }
          if (d > r + half_diag) {
            EXPECT_EQ(s, CellState::White) << i << j << k;
          }
          grey += s == CellState::Grey;
        }
    EXPECT_EQ(cc.stats().grey_cells, grey);
    EXPECT_EQ(cc.stats().grey_cells + cc.stats().black_cells + cc.stats().white_cells,
              long(n) * n * n);
    EXPECT_EQ(cc.stats().ambiguous_regions, 0);
    long faces = 0;
    for (const auto& c : cc.cells())
      if (c.state == CellState::Grey) faces += __builtin_popcount(c.config.domain_mask);
    EXPECT_EQ(faces, cc.stats().domain_faces);
    EXPECT_EQ(cc.distance().size(), size_t(faces) * 16 * 16);
  }
}

TEST(CellComplexBuild, EncodedSurfaceIsTheSphereAwayFromItsTexels) {
  // Points clearly inside or outside the sphere (more than a few texels of the finest cell's
  // map away) are classified by the distance maps as by the sphere itself, on every grid size;
  // N = 1 is one perspective cell (case 0), where the sphere is star-shaped about the centre.
  const glm::dvec3 centre(0.5, 0.5, 0.5);
  const double r = 0.37;
  const TriangleMesh sphere = test::uv_sphere(centre, r, 96, 48);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int n : {1, 2, 4, 8}) {
    SCOPED_TRACE("N " + std::to_string(n));
    const CellComplex cc = CellComplex::build(sphere, {.grid = n, .resolution = 32});
    const double band = 4.0 / (32 * n) + 3e-3;
    int tested = 0, wrong = 0;
    for (int i = 0; i < 20000; ++i) {
      const glm::dvec3 p(u01(rng), u01(rng), u01(rng));
      const double d = glm::length(p - centre);
      if (std::abs(d - r) < band) continue;
      ++tested;
      const bool bad = cc.encoded_inside(p) != (d < r);
      wrong += bad;
      if (bad) {
        const auto l = cc.lookup(p);
        const auto& cell = cc.cells()[cc.domain_faces()[std::max(0, l.face_index)].cell];
        std::printf(
            "p %.4f %.4f %.4f d-r %.4f case %s face %d st %.3f %.3f along %.3f len %.3f dist "
            "%.4f\n",
            p.x, p.y, p.z, d - r, cell_case_name(cell.config.base_case), l.line.face, l.st.x,
            l.st.y, l.line.along, l.line.length, cc.sample_distance(l.face_index, l.st));
      }
    }
    EXPECT_GT(tested, 10000);
    EXPECT_EQ(wrong, 0);
  }
}

TEST(CellComplexBuild, ANestedSheetIsOccludedAtN1AndSeparatedByAFinerGrid) {
  // Two concentric spheres (a hollow ball): from the centre (case 0) every line crosses both,
  // so half the fragments are occluded at N = 1; the automatic choice (Section 3.3.3) doubles
  // N until the ratio falls below its threshold, and reports each step.
  const TriangleMesh shell = test::hollow_ball();
  const CellComplex one = CellComplex::build(shell, {.grid = 1, .resolution = 16});
  EXPECT_NEAR(one.stats().occluded_ratio(), 0.5, 0.02);
  EXPECT_EQ(one.stats().multi_crossing_texels, 6 * 16 * 16);
  const CellComplex chosen =
      CellComplex::build(shell, {.grid = 0, .resolution = 16, .threshold = 0.05, .grid_max = 16});
  ASSERT_GE(chosen.stats().trials.size(), 2u);
  EXPECT_EQ(chosen.stats().trials.front().grid, 1);
  EXPECT_EQ(chosen.grid(), chosen.stats().trials.back().grid);
  EXPECT_TRUE(chosen.stats().occluded_ratio() < 0.05 || chosen.grid() == 16);
  for (size_t i = 1; i < chosen.stats().trials.size(); ++i)
    EXPECT_EQ(chosen.stats().trials[i].grid, 2 * chosen.stats().trials[i - 1].grid);
}

TEST(CellComplexMesh, ReconstructedVerticesLieOnTheSurfaceAndCoverIt) {
  // Section 3.5.1: every vertex is a texel's first crossing, unprojected: on the sphere up to
  // its tessellation and 16-bit rounding, at every level of detail.
  const glm::dvec3 centre(0.5, 0.5, 0.5);
  const double r = 0.37;
  const TriangleMesh sphere = test::uv_sphere(centre, r, 96, 48);
  for (int n : {1, 2, 4}) {
    const CellComplex cc = CellComplex::build(sphere, {.grid = n, .resolution = 32});
    for (int lod : {0, 2}) {
      SCOPED_TRACE("N " + std::to_string(n) + " lod " + std::to_string(lod));
      const CellMesh m = reconstruct_cell_mesh(cc, lod, 6);
      ASSERT_GT(m.triangles.size(), 100u);
      double worst = 0;
      for (const glm::vec3& p : m.position)
        worst = std::max(worst, std::abs(glm::length(glm::dvec3(p) - centre) - r));
      // A vertex averages a block's distances along converging lines: a chord's sag.
      EXPECT_LT(worst, lod == 0 ? 1e-2 : 4e-2);
      // Each surface point lies in one cell and projects onto one of its faces: the triangles
      // cover the sphere once, but for the cracks between faces.
      double area = 0;
      for (const glm::uvec3& t : m.triangles)
        area += 0.5 * glm::length(glm::cross(glm::dvec3(m.position[t.y] - m.position[t.x]),
                                             glm::dvec3(m.position[t.z] - m.position[t.x])));
      EXPECT_NEAR(area / (4 * M_PI * r * r), 1.0, lod == 0 ? 0.1 : 0.2);
    }
  }
}

}  // namespace
}  // namespace rl

namespace rl {
namespace {

TEST(CellComplexBuild, SerialisesExactlyAndRefusesForeignBytes) {
  // The precompute cache stores a complex as these bytes: read back it is the same complex;
  // cut short, padded or of another version it is refused (and rebuilt by the caller).
  const TriangleMesh sphere = test::uv_sphere({0.5, 0.5, 0.5}, 0.37, 48, 24);
  const CellComplex cc =
      CellComplex::build(sphere, {.grid = 0, .resolution = 8, .threshold = 0.05, .grid_max = 4});
  const std::vector<uint8_t> bytes = cc.serialize();
  CellComplex back;
  ASSERT_TRUE(CellComplex::deserialize(bytes, sphere, back));
  EXPECT_TRUE(back.stats().from_cache);
  EXPECT_EQ(back.grid(), cc.grid());
  EXPECT_EQ(back.distance(), cc.distance());
  EXPECT_EQ(back.face_inside(), cc.face_inside());
  EXPECT_EQ(back.crossings(), cc.crossings());
  EXPECT_EQ(back.normal(), cc.normal());
  EXPECT_EQ(back.color(), cc.color());
  EXPECT_EQ(back.stats().trials.size(), cc.stats().trials.size());
  EXPECT_EQ(back.stats().cases, cc.stats().cases);
  EXPECT_EQ(back.stats().construction_ms, cc.stats().construction_ms);
  EXPECT_EQ(back.mesh().triangles.size(), sphere.triangles.size());
  for (size_t i = 0; i < cc.cells().size(); ++i) {
    EXPECT_EQ(back.cells()[i].state, cc.cells()[i].state);
    EXPECT_EQ(back.cells()[i].config.base_case, cc.cells()[i].config.base_case);
  }
  for (int k = 0; k < 200; ++k) {
    const glm::dvec3 p(0.13 + 0.0037 * k, 0.5, 0.21 + 0.003 * k);
    EXPECT_EQ(back.encoded_inside(p), cc.encoded_inside(p));
  }
  std::vector<uint8_t> cut(bytes.begin(), bytes.end() - 3), padded = bytes, foreign = bytes;
  padded.push_back(0);
  foreign[0] ^= 0xff;
  CellComplex refused;
  EXPECT_FALSE(CellComplex::deserialize(cut, sphere, refused));
  EXPECT_FALSE(CellComplex::deserialize(padded, sphere, refused));
  EXPECT_FALSE(CellComplex::deserialize(foreign, sphere, refused));
}

}  // namespace
}  // namespace rl
