// Section 3.3.2's GPU sampling of a cell complex's distance and normal maps
// (gpu/cell_gpu_sampling.h) against the CPU's per-texel projection lines (relief/cell_complex.h):
// on a tessellated sphere (perspective and parallel cells) and on the Stanford bunny (axial ones
// too). The two agree to rounding where the cell's projection maps triangles onto triangles; in
// axial cells, whose projection bends straight edges (Figure 3), only once long edges are cut, as
// the paper's geometry shader does. Tolerances in face texels (64 or 32 per cell side).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gpu/cell_gpu_sampling.h"
#include "support/test_support.h"

namespace rl {
namespace {

using Type = CellProjection::Type;

void print(const char* what, const CellSamplingAgreement& a) {
  for (int k = 0; k < 4; ++k) {
    const CellSamplingAgreement::PerType& t = a.types[k];
    if (!t.texels) continue;
    std::printf(
        "%s, %s: %ld texels, %ld hit on the CPU, %ld on one side only (%ld at a line's end); "
        "error p99 %.3g, max %.3g texels; normals p99 %.3g, max %.3g deg, %ld over 1 deg; "
        "fragments %ld (%ld occluded) against %ld (%ld), %ld texels' counts differ\n",
        what, projection_type_name(Type(k)), t.texels, t.cpu_hits, t.one_sided, t.one_sided_at_ends,
        t.err_texels_p99, t.err_texels_max, t.normal_err_deg_p99, t.normal_err_deg_max,
        t.normal_over_1deg, t.gpu_fragments, t.gpu_occluded, t.cpu_fragments, t.cpu_occluded,
        t.fragment_counts_differ);
  }
}

// The same triangle's normal, to float rounding; a line through a triangle's edge, or one that
// grazes the surface where two triangles lie within rounding along it, may report either.
void expect_same_normals(const CellSamplingAgreement::PerType& t) {
  EXPECT_LT(t.normal_err_deg_p99, 1e-3);
  EXPECT_LE(double(t.normal_over_1deg), 5e-3 * double(t.both_hit));
}

// Section 3.3.3's count of the fragments that project onto each texel: the stencil's against the
// line's crossings, texel by texel; `differ` of the texels may part (where the line ends).
void expect_same_fragments(const CellSamplingAgreement::PerType& t, double differ) {
  EXPECT_LE(double(t.fragment_counts_differ), differ * double(t.texels));
  EXPECT_LE(std::abs(double(t.gpu_occluded - t.cpu_occluded)), 1e-3 * double(t.cpu_fragments));
}

// Where the projection is linear: the same texels hit, the same points to float rounding (a
// 32-bit float of d against a 16-bit quantised one: 1/65535 of a line of up to ~1.7 cells).
void expect_linear_agreement(const CellSamplingAgreement::PerType& t) {
  ASSERT_GT(t.cpu_hits, 1000);
  EXPECT_LE(double(t.one_sided), 1e-4 * double(t.texels));
  EXPECT_GE(double(t.within_half), (1 - 1e-4) * double(t.both_hit));
  EXPECT_LT(t.err_texels_p99, 0.01);
  expect_same_normals(t);
  expect_same_fragments(t, 1e-4);
}

TEST(CellGpuSampling, PerspectiveAndParallelCellsMatchTheProjectionLines) {
  const TriangleMesh sphere = test::uv_sphere({0.5, 0.5, 0.5}, 0.37, 96, 48);
  const CellComplex cc = CellComplex::build(sphere, {.grid = 4, .resolution = 64});
  const CellGpuSampling gpu = sample_cell_maps_on_gpu(cc, {});
  EXPECT_EQ(gpu.face_draws, long(cc.domain_faces().size()));
  const CellSamplingAgreement a = compare_cell_sampling(cc, gpu);
  print("sphere", a);
  expect_linear_agreement(a.types[int(Type::Perspective)]);
  expect_linear_agreement(a.types[int(Type::Parallel)]);
}

TEST(CellGpuSampling, AxialCellsAgreeOnlyOnceLongEdgesAreCut) {
  // In its bounding cube's texture space, y up, as a scene's cell complex has it.
  const TriangleMesh file =
      load_mesh(std::string(RELIEFLAB_SOURCE_DIR) + "/assets/meshes/bunny.obj");
  const TriangleMesh bunny = to_frame(file, cell_frame(file, 1));
  const CellComplex cc = CellComplex::build(bunny, {.grid = 8, .resolution = 32});
  const CellSamplingAgreement chords = compare_cell_sampling(cc, sample_cell_maps_on_gpu(cc, {}));
  const CellSamplingAgreement cut =
      compare_cell_sampling(cc, sample_cell_maps_on_gpu(cc, {.subdivide_texels = 1}));
  print("bunny, edges drawn as chords", chords);
  print("bunny, edges cut to a texel", cut);
  const CellSamplingAgreement::PerType &bent = chords.types[int(Type::Axial)],
                                       &fixed = cut.types[int(Type::Axial)];
  ASSERT_GT(bent.cpu_hits, 1000);
  // As chords, the projected triangles miss or cover the wrong texels...
  EXPECT_GT(double(bent.one_sided), 0.02 * double(bent.texels));
  EXPECT_GT(bent.err_texels_p99, 1.0);
  EXPECT_GT(bent.normal_err_deg_p99, 1.0);  // points of other triangles
  EXPECT_GT(double(bent.fragment_counts_differ), 0.02 * double(bent.texels));
  // ...cut, they follow the curves: what still differs is where a line meets the surface at
  // its end, on the face or at the axis, where every line of the cell meets.
  EXPECT_LE(double(fixed.one_sided), 0.005 * double(fixed.texels));
  EXPECT_GE(double(fixed.one_sided_at_ends), 0.5 * double(fixed.one_sided));
  EXPECT_LT(double(bent.one_sided_at_ends), 0.1 * double(bent.one_sided));
  EXPECT_GE(double(fixed.within_half), 0.999 * double(fixed.both_hit));
  EXPECT_LT(fixed.err_texels_p99, 0.05);
  expect_same_normals(fixed);
  expect_same_fragments(fixed, 0.005);
  // Cutting touches only the axial cells.
  expect_linear_agreement(cut.types[int(Type::Perspective)]);
  EXPECT_EQ(cut.types[int(Type::Perspective)].one_sided,
            chords.types[int(Type::Perspective)].one_sided);
}

// What a scene with sampling = "gpu" draws: the complex with the GPU's maps taken in. The CPU's
// own maps taken in give back the complex unchanged; the GPU's move each distance by at most a
// few of its 16-bit steps (a 32-bit float against the CPU's quantised line).
TEST(CellGpuSampling, SampledMapsReplaceTheComplexsOwn) {
  const CellComplex cc = CellComplex::build(test::uv_sphere({0.5, 0.5, 0.5}, 0.37, 96, 48),
                                            {.grid = 4, .resolution = 32});
  std::vector<float> own(cc.distance().size());
  for (size_t t = 0; t < own.size(); ++t)
    own[t] = cc.crossings()[t] ? float(cc.distance()[t] / cc.distance_scale()) : 1.0f;
  const CellComplex same = cc.with_sampled_maps(own, cc.normal());
  EXPECT_EQ(same.distance(), cc.distance());
  EXPECT_EQ(same.normal(), cc.normal());

  const CellComplex gpu = with_gpu_sampled_maps(cc);
  long hits = 0, moved = 0;
  for (size_t t = 0; t < cc.distance().size(); ++t) {
    if (!cc.crossings()[t]) {
      // Missed on the CPU, and on the GPU too (the sphere has no one-sided texels): the CPU's d.
      EXPECT_EQ(gpu.distance()[t], cc.distance()[t]);
      continue;
    }
    ++hits;
    moved += std::abs(int(gpu.distance()[t]) - int(cc.distance()[t])) > 4;
  }
  ASSERT_GT(hits, 1000);
  EXPECT_LE(double(moved), 1e-3 * double(hits));
  EXPECT_THROW((void)cc.with_sampled_maps(std::vector<float>(3, 1.0f), cc.normal()),
               std::invalid_argument);
}

TEST(CellGpuSampling, MapsOfTheWrongSizeAreRefused) {
  const CellComplex cc = CellComplex::build(test::uv_sphere({0.5, 0.5, 0.5}, 0.3, 24, 12),
                                            {.grid = 2, .resolution = 8});
  CellGpuSampling wrong;
  wrong.distance.assign(7, 1.0f);
  wrong.normal.assign(7, glm::vec3(0.0f));
  EXPECT_THROW(compare_cell_sampling(cc, wrong), std::invalid_argument);
}

}  // namespace
}  // namespace rl
