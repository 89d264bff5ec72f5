#pragma once
// What a technique promises, as data in its describe() (TechniqueInfo::contract), so that the
// contract suite (tests/contract/, CTest label `contract`) can hold every registered technique
// -- one dropped into techniques/ tomorrow included -- to its own word: the kind of answer it
// gives, the most texture fetches a pixel can cost, which parameters buy accuracy and in which
// direction, and the accuracy it states.
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/params.h"

namespace rl {

// The kind of answer a technique gives to "where does this ray meet the relief?".
enum class Answer {
  Exact,          // the first hit on the bilinear surface (or the mesh), up to float rounding
  Converging,     // a search whose error shrinks to zero as its accuracy knobs grow
  Approximation,  // an estimate with no setting that makes it exact
  ShadingOnly,    // no search: it shades the base point (normal mapping)
};
std::string answer_name(Answer a);

// The surface a search answers on: the depth map as GL_LINEAR reconstructs it (bilinear
// patches between texel centres), or as GL_NEAREST does (a flat-topped column per texel).
enum class Surface { Bilinear, TexelColumns };

// What a worst-case fetch count (or a stated accuracy) may depend on: the parameters, the
// map, and the ray.
struct RayQuery {
  ParamValues params;
  int map_width = 0, map_height = 0;  // texels
  int layer_groups = 1;               // RGBA texels per layered texel (4 layers each)
  int faces = 1;                      // heightfield maps of an object (one per cube face)
  int grid_cells = 0;                 // cells per side of a cell complex's grid
  // The ray's lateral travel across the relief's whole depth range (depth 0 to 1), in texels
  // along u and along v (absolute values): what a walk over cells pays for.
  glm::dvec2 span_texels{0};
  double param(const std::string& name) const { return params.at(name); }
};

struct ReliefMap;
// The query for a whole frame of `map` with `params`: its sizes, and the longest span a ray
// can have (one across the map a thousand times over, so that a walk's bound is its cap): a
// fragment of any view is within the bound this gives.
RayQuery whole_frame_query(const ParamValues& params, const ReliefMap& map);

// The most cells the texel-centre walk (harness/glsl/centerline_walk.glsl) visits on a ray:
// its first cell and one per centerline crossed, and never more than its cap (RL_MAX_CELLS).
inline constexpr double kWalkCellCap = 16384;
double walk_cells(const RayQuery& q);
// The most nodes the min-depth quadtree search (harness/glsl/min_depth_quadtree.glsl) visits,
// one fetch each: a monotone ray enters each node of each level at most once.
double quadtree_nodes(const RayQuery& q);

// A linear search of `linear_steps` over the depth range refined by `binary_steps` bisections
// (chapter 5's Listing 5.3 and its kin): its stated t error, one step / 2^binary_steps, and
// the stretch it may step over, one step.
double linear_binary_t_error(const RayQuery& q);
double one_linear_step(const RayQuery& q);
// Its most fetches, linear_steps + binary_steps, + 2 to shade (normal and colour).
double linear_binary_fetches_shaded(const RayQuery& q);

// A parameter that trades fetches for accuracy.
struct AccuracyKnob {
  std::string param;
  bool larger_is_finer = true;  // false: accuracy grows as the value falls (a level of detail)
};

// A linear + binary search's knobs (both larger is finer) and their finest values: 1024 steps
// refined 16 times.
std::vector<AccuracyKnob> linear_binary_knobs();
ParamValues linear_binary_finest();
// Its two parameters, declared alike by every technique that runs the search: kind, range
// (linear 1-4096, binary 0-32) and define (RL_LINEAR_STEPS, RL_BINARY_STEPS) here; the default
// and the paper's words for it the technique's.
ParamSpec linear_steps_param(int default_steps, const std::string& doc);
ParamSpec binary_steps_param(int default_steps, const std::string& doc);

struct TechniqueContract {
  Answer answer = Answer::Approximation;
  // What an exact or converging answer is exact on, or converges to, at its finest setting.
  Surface surface = Surface::Bilinear;
  // The most texture fetches one fragment of a plain render (no shadow, no ambient occlusion)
  // can cost, kept or discarded -- its search and its shading -- and one probe ray (its
  // search); null: undeclared.
  std::function<double(const RayQuery&)> max_fetches{};
  std::string max_fetches_formula{};  // the same, in words ("linear_steps - 1 + binary_steps + 2")
  std::vector<AccuracyKnob> knobs{};
  // Converging: the setting of its knobs where it is most accurate, for the stated accuracy
  // and the convergence checks (the other parameters keep their defaults).
  ParamValues finest{};
  // The stated accuracy: the largest distance, in depth units along the ray's parameter t, of
  // the hit from the first crossing of the surface, on surfaces with no feature thinner than
  // the search resolves (see `accuracy`); null: none stated.
  std::function<double(const RayQuery&)> t_error{};
  std::string accuracy{};  // the stated accuracy and its conditions, in words
  // The condition on the surface: the longest stretch of t a ray may spend inside the relief
  // and still be missed (one linear step); the stated accuracy holds where the first crossing
  // leads into a stretch at least this long. Null: no condition.
  std::function<double(const RayQuery&)> t_resolution{};
  // It has a ray search the probe mode runs (a rasteriser has none).
  bool ray_probe = true;
  // Its search stops on the surface or just inside (a hit is never above the surface).
  bool hits_from_inside = true;
};

// Throws std::logic_error naming `technique` when the contract is incomplete or names a
// parameter `params` does not declare (checked at registration, like the parameters).
void check_contract(const std::string& technique, const TechniqueContract& contract,
                    const std::vector<ParamSpec>& params);

}  // namespace rl
