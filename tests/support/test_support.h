#pragma once
// Helpers shared by the tests: small scenes, one technique rendered into a G-buffer, its
// truth, and a scratch folder per test.
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "config/config.h"
#include "core/gbuffer.h"
#include "core/triangle_mesh.h"
#include "metrics/fragment_cost.h"
#include "metrics/metrics.h"
#include "relief/relief_map.h"
#include "scene/scene.h"
#include "technique/technique.h"
#include "truth/truth_render.h"

namespace rl::test {

// A planar scene with a procedural relief (float textures unless quantize is set).
SceneDesc procedural_scene(const std::string& kind, int resolution, double depth = 0.08,
                           bool quantize = false,
                           const std::map<std::string, double>& options = {});

// The weave of Figure 5 baked into 4 layers on a planar base (tile 2, depth 0.15), empty
// floor, measured against `truth` (the woven mesh, or its own layers).
SceneDesc weave_scene(int resolution, TruthLevel truth);

struct Measured {
  GBuffer technique;
  GBuffer truth;
  ImageMetrics metrics;
  TruthStats truth_stats;
  FragmentCounts counts;  // every fragment the technique shaded (metrics/fragment_cost.h)
};

// Renders `technique` with `params` on `scene` at `view` into a size x size G-buffer and
// measures it against a freshly traced truth.
// `truth_tolerance` is the truth's stated tessellation tolerance (depth units).
Measured measure(const SceneDesc& scene, const std::string& technique, const ParamValues& params,
                 const View& view, int size = 96, double truth_tolerance = 2e-3);

// Random tangent-space rays (u, v, depth)(t) = origin + t direction with direction.z = 1:
// origins u, v in [-1, 2) at depth `start_depth`, elevations in [min_el, max_el] degrees,
// any azimuth; `aspect` = world relief depth / world length of one u (lateral texture units
// per depth unit = aspect / tan(elevation)).
struct TangentRay {
  glm::dvec3 origin, direction;
};
std::vector<TangentRay> random_tangent_rays(int n, double min_el, double max_el, double aspect,
                                            unsigned seed, double start_depth);
std::vector<ProbeRay> as_probe_rays(const std::vector<TangentRay>& rays);

// A w x h map with these depths (row 0 first), flat normals and white colour.
ReliefMap map_from_depths(int w, int h, const std::vector<float>& depths);
// `relief` (a procedural kind) on a curved base (sphere, torus, cylinder...) of 32 segments.
SceneDesc curved_scene(const std::string& base, const std::string& relief, int res, double depth);

// An n x n map of uniformly random depths (seeded): every texel a feature, the hardest surface
// for a search.
ReliefMap random_map(int n, unsigned seed);

// `technique` at `params`, prepared on `map`, run on `rays` (Technique::probe: depth_aspect is
// world depth over the world length of a unit of u and of v).
std::vector<ProbeHit> probe(const std::string& technique, const ParamValues& params,
                            const ReliefMap& map, const GpuRelief& relief,
                            const std::vector<ProbeRay>& rays,
                            glm::dvec2 depth_aspect = glm::dvec2(0.08));
// The same on `map` uploaded for the call (the shared GL context made if need be).
std::vector<ProbeHit> probe(const std::string& technique, const ParamValues& params,
                            const ReliefMap& map, const std::vector<ProbeRay>& rays,
                            glm::dvec2 depth_aspect = glm::dvec2(0.08));

// A UV sphere of radius r about c (slices x stacks quads, poles as fans), counter-clockwise seen
// from outside.
TriangleMesh uv_sphere(glm::dvec3 c, double r, int slices, int stacks);

// Two concentric UV spheres about (0.5, 0.5, 0.5), radii 0.4 and 0.2, the inner one turned
// inside out: a hollow ball, whose every line from the centre crosses two sheets.
TriangleMesh hollow_ball();

// Axis-aligned boxes in a pattern's mesh space (x = u, y = v, z = -depth), outward-wound
// unless `flip`; each box spans u, v in [lo, hi] and depth [top, bottom]: layers with known
// crossings.
TriangleMesh layer_boxes(const std::vector<std::tuple<double, double, double, double>>& spans,
                         bool flip = false);

// Writes `mesh` as an OBJ file at `path` (its folder created); returns the path.
std::string write_obj(const TriangleMesh& mesh, const std::string& path);
// A fresh, empty folder under the build's temporary directory.
std::string scratch_dir(const std::string& name);

// read_precompute_cache called from this file's folder (tests/support/): code in another folder
// than the caller's test, whose entries must not be read as its own (core/precompute_cache.h).
bool read_precompute_cache_elsewhere(const std::string& folder, const std::string& options,
                                     uint64_t map_hash, void* out, size_t bytes);

// Parses the sweep config `toml` (relative paths resolved from `dir`) and runs it quietly
// into dir + "/out"; returns the parsed config (expand_cells(config) gives its cell keys).
SweepConfig run_sweep_in(const std::string& toml, const std::string& dir);

// The rows run_sweep_in(..., dir) stored for `config`, by scene name: for sweeps of one cell per
// scene. Throws naming the cell when a row is missing or two cells share a scene.
std::map<std::string, nlohmann::json> rows_by_scene(const SweepConfig& config,
                                                    const std::string& dir);

// A sweep of 4 cells (relief at 8 and 16 steps, 45 and 20 degrees, 32^2 bricks) written to
// dir/sweep.toml (the folder created); `sweep_extra` adds [sweep] keys. Returns its path.
std::string write_small_sweep(const std::string& dir, const std::string& sweep_extra);

// Runs `sql` on the result store at `db_path` (a test damaging or editing it as a user could).
void store_exec(const std::string& db_path, const std::string& sql);

// Runs the relieflab CLI with `args`; returns its exit status, stderr+stdout in `output`.
// `prefix` goes before the program (e.g. setpriv to run it as another user).
int run_cli(const std::string& args, std::string& output, const std::string& prefix = "");

}  // namespace rl::test
