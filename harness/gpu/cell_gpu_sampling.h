#pragma once
// A cell complex's distance and normal maps sampled on the GPU, as Apaza & Andujar build them
// (Section 3.3.2): for every grey cell and each of its domain faces, an orthographic view of that
// face, the mesh triangles that cross the cell drawn through a geometry shader that projects them
// by the cell's projection, and a fragment shader that writes each surface point's distance from
// its face point as its depth, so that the depth test keeps the nearest, and its normal beside it
// (harness/glsl/cell_sampling_*.glsl); the stencil buffer counts the fragments per texel, whose
// occluded share Section 3.3.3 chooses the grid size by. relief/cell_complex.h samples the same
// maps on the CPU by casting every texel's own projection line; the two agree where the
// projection maps triangles onto triangles (perspective, planar, parallel), and the GPU's bend
// where it does not (axial) unless long edges are cut first.
#include <array>
#include <vector>

#include "relief/cell_complex.h"

namespace rl {

struct CellGpuSamplingOptions {
  // In axial cells, cut a triangle whose projected edges are longer than this many face texels
  // into up to 8 x 8 pieces first; 0: never (the projection's curves drawn as chords).
  double subdivide_texels = 0;
};

struct CellGpuSampling {
  // Per texel of every domain face, in CellComplex::distance()'s order: the nearest surface
  // point's distance from the face point as a share of the projection line in the cell; 1 where
  // no surface point projects there.
  std::vector<float> distance;
  // Per texel, the unit normal of the surface point's triangle (Embree's Ng convention, as the
  // CPU's maps hold it); 0 where there is none.
  std::vector<glm::vec3> normal;
  // Per texel, how many fragments (surface points of the cell) project onto it, counted in the
  // stencil buffer as Section 3.3.3 estimates the occluded fragments (at most 255).
  std::vector<uint8_t> fragments;
  double ms = 0;        // every face drawn and read back: the wall clock after glFinish
  long face_draws = 0;  // domain faces drawn
  long triangles = 0;   // mesh triangles submitted, over every face drawn
};

// Needs the process's GL context (gl/context.h); throws GlError where the driver refuses.
CellGpuSampling sample_cell_maps_on_gpu(const CellComplex& cells,
                                        const CellGpuSamplingOptions& options);

// The complex with the distance and normal maps sampled on the GPU, axial cells' triangles cut to
// a face texel (CellComplex::with_sampled_maps): what a scene with cells sampling = "gpu" draws.
CellComplex with_gpu_sampled_maps(const CellComplex& cells);

// How the GPU's maps compare with the CPU's (CellComplex::distance(), normal(), crossings()), per
// projection type (CellProjection::Type's order): texels whose line meets the surface on one side
// only; the position error in face texels (|difference of d| x the line's length) and the angle
// between the two normals where both do; and the fragments counted per texel.
struct CellSamplingAgreement {
  struct PerType {
    long texels = 0;     // of this type's domain faces
    long cpu_hits = 0;   // texels whose projection line meets the surface (CPU)
    long both_hit = 0;   // ... and the GPU's map holds a surface point there too
    long one_sided = 0;  // a surface point on one side only
    // ... that lies at an end of its projection line: on the face itself (d < 1e-4) or within
    // 1% of the line's inner end (d > 0.99: the centre or axis, where every line meets)
    long one_sided_at_ends = 0;
    long within_half = 0;  // of both_hit, within half a face texel of the CPU's point
    long over_one = 0;     // of both_hit, more than a face texel from it
    double err_texels_max = 0, err_texels_p99 = 0, err_texels_mean = 0;
    long normal_over_1deg = 0;  // of both_hit, normals more than a degree apart
    double normal_err_deg_max = 0, normal_err_deg_p99 = 0, normal_err_deg_mean = 0;
    // Fragments per texel: the GPU's stencil count against the CPU's crossings of the line.
    long gpu_fragments = 0, cpu_fragments = 0;  // over the type's texels
    long gpu_occluded = 0, cpu_occluded = 0;    // of those, behind a texel's first
    long fragment_counts_differ = 0;            // texels whose two counts differ
  };
  std::array<PerType, 4> types;
};

// Throws std::invalid_argument when the GPU's maps are not the complex's size.
CellSamplingAgreement compare_cell_sampling(const CellComplex& cells, const CellGpuSampling& gpu);

}  // namespace rl
