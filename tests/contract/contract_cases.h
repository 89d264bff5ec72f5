#pragma once
// The cases the technique contract (test_contract.cpp) holds every registered technique to:
// heightfield maps with closed-form or exactly reconstructed surfaces probed by hard rays, and
// whole frames of scenes with their truths. Which technique meets which case is decided by
// what it declares (cannot_render, contract.ray_probe), never by its name.
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/gbuffer.h"
#include "core/op_kinds.h"
#include "metrics/metrics.h"
#include "relief/relief_map.h"
#include "scene/scene.h"
#include "technique/technique.h"

namespace rl::contract {

// Lateral texture units per depth unit of a probe ray at 45 degrees (world depth / world
// length of u): the probes' depth_aspect.
inline constexpr double kProbeAspect = 0.08;

// A heightfield map and what it stands for.
struct ProbeMap {
  std::string name;
  ReliefMap map;
  // No feature thinner than a texel: a converging search at its finest setting resolves it.
  bool smooth = false;
};

// Tilted planes (across the tiling seam: a full-depth jump), a saddle (reproduced exactly by
// bilinear cells), smooth sines, bricks with full-depth joints, one-texel spikes, a flat top
// and an empty (all-floor) map; 64 x 64 but for one 128 x 32 strip.
const std::vector<ProbeMap>& probe_maps();

// Rays from 1 to 90 degrees, every azimuth (the axes and diagonals included), starting on and
// around the texture's borders and anywhere in the tiles around it, at depth 0; with
// `from_inside`, one in eight starts inside the depth range instead (a ray entering a box
// proxy's side), else at depth 0 too. Ray i is the same ray in every call.
std::vector<ProbeRay> hard_rays(bool from_inside);
// Rays whose base is curved (ProbeRay::quadric), for techniques that bend their ray.
std::vector<ProbeRay> curved_rays();

// The closed-form answer of a probe ray on `surface`: the CPU reference.
struct ReferenceAnswer {
  bool hit = false;
  double t = 0;
  // A ray exactly on a boundary between texel columns may take either (GL_NEAREST decides by
  // rounding): the answer on the other side; the same as above elsewhere.
  bool other_hit = false;
  double other_t = 0;
};
ReferenceAnswer reference(const ReliefMap& map, const ProbeRay& ray,
                          Surface surface = Surface::Bilinear);
// The depth of `surface` at (u, v).
double surface_depth(const ReliefMap& map, Surface surface, double u, double v);

// How long, in t, `ray` stays inside the relief after entering it at t_hit, looked at up to
// `up_to` (a stretch that long or longer returns up_to; one leaving through the floor counts as
// inside): whether a search that steps `up_to` at a time is promised to see the crossing.
double inside_stretch(const ReliefMap& map, Surface surface, const ProbeRay& ray, double t_hit,
                      double up_to);

// What a fetch bound may depend on for `ray` on `map`.
RayQuery ray_query(const ParamValues& params, const ReliefMap& map, const ProbeRay& ray);

// Distance between two points of texture space (u, v, depth), in texels of `map` (a depth unit
// is kProbeAspect texture units long, as the probes are run).
double texel_distance(const ReliefMap& map, glm::dvec3 a, glm::dvec3 b);

// How far GL_LINEAR's filtering of `map` may be from the exact bilinear depth (llvmpipe rounds
// its weights to 8 bits): the largest jump between neighbouring texels / 256, and the steepest
// slope in depth per texture unit.
double filtering_tolerance(const ReliefMap& map);
double steepest_slope(const ReliefMap& map);
// The same near (u, v): the largest jump among the 4 x 4 texels around it / 256.
double filtering_tolerance_at(const ReliefMap& map, double u, double v);
// How far along t a depth error of `depth_error` moves the crossing of `ray` with the bilinear
// surface at t_hit: depth_error over the rate at which the ray goes below the surface there
// (at least 0.05: a ray running along the surface).
double depth_error_along_ray(const ReliefMap& map, const ProbeRay& ray, double t_hit,
                             double depth_error);

// Runs `technique` with `params` on `rays` in probe mode on `map`, whose world depth is
// `depth_aspect` times the world length of a texture unit.
std::vector<ProbeHit> probe(const std::string& technique, const ParamValues& params,
                            const ReliefMap& map, const std::vector<ProbeRay>& rays,
                            glm::dvec2 depth_aspect = glm::dvec2(kProbeAspect));

// A whole frame of a scene and its truth.
struct RenderCase {
  std::string name;
  SceneDesc scene;
  View view;
  bool planar_rays = false;  // a planar base seen from above: pixel rays enter at depth 0
  // What its truth traces: the map's own bilinear heightfield on a planar base (what an exact
  // heightfield search answers), or the source mesh a cell complex encodes (what a rasteriser of
  // that mesh answers); neither: layers, a curved base, cells or an object's faces.
  bool truth_is_the_map = false;
  bool truth_is_the_source_mesh = false;
};
const std::vector<RenderCase>& render_cases();

struct Frame {
  GBuffer image, truth;
  FragmentCounts counts;  // every fragment shaded, discarded ones included
  ImageMetrics metrics;
  RayQuery query;  // the case's map, with the longest lateral span of any pixel's ray
  std::vector<std::pair<std::string, double>> columns;  // the technique's frame_columns()
  std::vector<ProbeRay> pixel_rays;  // planar_rays cases: each pixel's tangent ray (else empty)
  glm::dvec2 depth_aspect{0};        // planar_rays cases: the base's, for probing pixel_rays
  const ReliefMap* map = nullptr;
};
// Renders case `index` (its asset and truth built once per process; each case, technique and
// setting drawn once per process).
Frame render(size_t index, const std::string& technique, const ParamValues& params);

// What each pixel's fragments executed, by kind, in case `index`'s timed frame drawn once in
// its op-counting form (gl/op_counting.h).
PixelOpCounts count_ops(size_t index, const std::string& technique, const ParamValues& params);

// The digests of the programs each of two successive frames of case `index` requested from the
// shader library (one technique instance, prepared once): a run records what a row was drawn
// with from these requests (run/cell_provenance.h), so every frame must make them.
std::pair<std::set<std::string>, std::set<std::string>> programs_of_two_frames(
    size_t index, const std::string& technique, const ParamValues& params);

// The registry's names, for parameterising the contract's tests.
std::vector<std::string> technique_names();
const TechniqueInfo& info_of(const std::string& technique);
// The technique's defaults, with `overrides`.
ParamValues settings(const std::string& technique, const ParamValues& overrides = {});
// The same, or nothing when the technique's validate() refuses the combination.
std::optional<ParamValues> valid_settings(const std::string& technique,
                                          const ParamValues& overrides);

}  // namespace rl::contract
