// Apaza & Andujar, Section 3.3.2: the distance and normal maps of a cell complex sampled on the
// GPU -- each grey cell's triangles drawn onto each of its domain faces through a geometry shader
// that projects them by the cell's projection, the depth test keeping the nearest surface point
// (gpu/cell_gpu_sampling.h) -- against the CPU's sampling, which casts every texel's own
// projection line (relief/cell_complex.h). Per mesh, setting (axial edges cut or not) and
// projection type: how many texels see the surface on one side only (and how many of those at an
// end of the projection line), how far apart the two put it where both do, in face texels, the
// angle between their normals there, how many fragments each counts per texel (the GPU in the
// stencil buffer, Section 3.3.3), and what each sampling took on this machine.
//
// Rows to stdout (scripts/cell-gpu-sampling-rows.sh makes results/apaza-gpu-sampling/rows.csv).
//   cell_gpu_sampling [--meshes bunny,teapot,dragon] [--runs 3]
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "bench_support.h"
#include "config/config.h"
#include "gl/context.h"
#include "gpu/cell_gpu_sampling.h"
#include "scene/relief_asset.h"

namespace rl {
namespace {

// The fastest of `runs` samplings after one to warm up (the first compiles the program).
CellGpuSampling fastest_sampling(const CellComplex& cc, double subdivide, int runs) {
  (void)sample_cell_maps_on_gpu(cc, {.subdivide_texels = subdivide});
  CellGpuSampling best;
  for (int i = 0; i < runs; ++i) {
    CellGpuSampling s = sample_cell_maps_on_gpu(cc, {.subdivide_texels = subdivide});
    if (i == 0 || s.ms < best.ms) best = std::move(s);
  }
  return best;
}

void print_rows(const std::string& mesh, const CellComplex& cc, double subdivide,
                const CellGpuSampling& gpu) {
  const CellSamplingAgreement a = compare_cell_sampling(cc, gpu);
  long all = 0;
  for (const auto& t : a.types) all += t.texels;
  for (int k = 0; k < 4; ++k) {
    const CellSamplingAgreement::PerType& t = a.types[k];
    if (t.texels == 0) continue;
    const double texels = double(t.texels), both = std::max<double>(1, double(t.both_hit));
    std::printf("%s,%d,%zu,%g,%s,%ld,%.4g,%.4g,", mesh.c_str(), cc.grid(), cc.domain_faces().size(),
                subdivide, projection_type_name(CellProjection::Type(k)), t.texels,
                100.0 * texels / double(all), 100.0 * double(t.cpu_hits) / texels);
    std::printf("%.4g,%.4g,%ld,%ld,%ld,%ld,%.4g,%.4g,%.4g,", 100.0 * double(t.one_sided) / texels,
                100.0 * double(t.within_half) / both, t.one_sided, t.one_sided_at_ends,
                t.one_sided - t.one_sided_at_ends, t.over_one, t.err_texels_mean, t.err_texels_p99,
                t.err_texels_max);
    std::printf("%ld,%.4g,%.4g,%.4g,%.4g,", t.normal_over_1deg,
                100.0 * double(t.normal_over_1deg) / both, t.normal_err_deg_mean,
                t.normal_err_deg_p99, t.normal_err_deg_max);
    const auto ratio = [](long part, long whole) {
      return whole ? double(part) / double(whole) : 0.0;
    };
    std::printf("%ld,%ld,%.4g,%.4g,%.4g,", t.gpu_fragments, t.cpu_fragments,
                ratio(t.gpu_occluded, t.gpu_fragments), ratio(t.cpu_occluded, t.cpu_fragments),
                100.0 * double(t.fragment_counts_differ) / texels);
    std::printf("%ld,%.4g,%.4g,%s\n", gpu.triangles, gpu.ms, cc.stats().sample_ms,
                cc.stats().from_cache ? "cache" : "built");
  }
  std::fflush(stdout);
}

void run(const std::vector<std::string>& meshes, int runs) {
  GlContext::shared();
  std::printf(
      "mesh,grid,domain_faces,subdivide_texels,projection,texels,texels_pct,cpu_hit_pct,"
      "one_sided_pct,within_half_texel_pct,one_sided_texels,one_sided_at_line_ends,"
      "one_sided_elsewhere,over_one_texel,"
      "pos_err_texels_mean,pos_err_texels_p99,pos_err_texels_max,"
      "normal_over_1deg,normal_over_1deg_pct,"
      "normal_err_deg_mean,normal_err_deg_p99,normal_err_deg_max,"
      "gpu_fragments,cpu_fragments,gpu_occluded_ratio,cpu_occluded_ratio,"
      "fragment_counts_differ_pct,"
      "triangles_drawn,gpu_sample_ms,cpu_sample_ms,cpu_maps\n");
  for (const std::string& mesh : meshes) {
    const SweepConfig config = bench::table1_mesh_config(mesh, "cell_gpu_sampling");
    const ReliefMap map = build_relief_asset(config.scenes.front(), 64);
    for (double subdivide : {0.0, 4.0, 1.0})
      print_rows(mesh, *map.cells, subdivide, fastest_sampling(*map.cells, subdivide, runs));
  }
}

}  // namespace
}  // namespace rl

int main(int argc, char** argv) {
  std::vector<std::string> meshes = {"bunny", "teapot", "dragon"};
  int runs = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--meshes"))
      meshes = rl::bench::split(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--runs"))
      runs = std::atoi(argv[i + 1]);
    else {
      std::fprintf(stderr, "cell_gpu_sampling: unknown option %s\n", argv[i]);
      return 2;
    }
  }
  if (runs < 1) {
    std::fprintf(stderr, "cell_gpu_sampling: --runs at least 1\n");
    return 2;
  }
  try {
    rl::run(meshes, runs);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cell_gpu_sampling: %s\n", e.what());
    return 1;
  }
  return 0;
}
