#pragma once
// Truth for a relief on a curved base (DESIGN.md: "a heightfield on a curved base"; chapter
// 5's silhouettes approximate it): the base mesh as drawn -- its flat triangles, with normals,
// uvs and tangents interpolated -- each point moved inward along the interpolated unit normal by
// depth x d(u, v), d the map's bilinear depth (or a meta-relief's combination), found to double
// rounding rather than tessellated. Two stages per ray, as the heightfield truth has them:
//
// 1. Embree traces a sheet that lies outside the relief everywhere (truth/shell_sheets.h): the
//    ray cannot meet the relief before it enters the sheet.
// 2. From there the ray is walked through the base triangles' prisms (truth/base_prisms.h) in
//    their own parameters: in a prism, uv is affine in the barycentrics, so the ray becomes a
//    curve in the map's texture space (u, v, depth). The walk follows it by chords, each kept
//    within 1e-2 texel of the ray (checked at three points; a chord strays as its length
//    squared, which sets the next one's length), and solves each against the map exactly
//    (relief/heightfield_reference.h's bilinear patches, or the meta-relief's union cells),
//    pushed down by its stray (along the fibre, and across it times the map's steepest step):
//    where that misses, the ray misses. Where it does not, the chord is halved until it lies
//    within 1e-5 texel of the ray and its own crossing is the hit; that last stray is the hit's
//    stated bound (DisplacedHit::off_ray) besides rounding. Where the ray climbs out above the
//    sheet, Embree takes over again.
//
// The relief is solid below its surface, as the heightfield truth's is: a ray meets it where it
// first goes at or below d (a shadow ray starting inside is occluded at once). Shadow and
// hemisphere rays only ask whether it is met, and take the walk's chords' answer (to 1e-2
// texel) without halving them. The sheet is entered only from outside, so a ray reaching the
// shell from within the object (through an open mesh) passes; at an edge where the normals
// split (a cube's), the two faces' shells overlap or part, as the techniques' do. Where the base
// bends faster than the shell is deep, prisms fold and the walk follows one prism's extension.
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "core/sharded_counter.h"
#include "relief/relief_map.h"
#include "scene/base_mesh.h"
#include "truth/base_prisms.h"
#include "truth/min_pyramid.h"
#include "truth/shell_sheets.h"
#include "truth/truth_surface.h"

namespace rl {

class MetaReliefTruth;

struct DisplacedHit {
  bool hit = false;
  double t = 0;         // world distance along the (unit) ray
  glm::dvec3 position;  // world
  glm::dvec2 uv;
  glm::dvec3 tangent, bitangent, normal;  // the base's unit frame at the hit (shading)
  // The traced surface's own unit normal there (the hit triangle's, facing the ray): what a
  // vertical error of the truth moves the hit along (truth_hit_bound).
  glm::dvec3 geometric_normal{0, 0, 1};
  // The surface's own shading normal (world, facing the ray) and colour, where the truth has
  // them (a pattern mesh on the base); otherwise the map's at `uv` in the frame above.
  bool has_surface = false;
  glm::dvec3 surface_normal{0}, albedo{0};
  // How far (world) the reported hit may lie off the ray, besides the truth's stated bounds:
  // the exact walk's last chord (DisplacedTruth); the pixel's bound divides it by the cosine
  // at the surface.
  double off_ray = 0;
  int base_triangle = -1;  // the base triangle under the hit, where the truth knows it
};

class DisplacedTruth {
 public:
  // `depth`: world depth of depth 1. `texels_per_sheet_edge` and `max_sheet_triangles` set
  // the front end's sheet (a speed knob: how far the exact walk goes).
  DisplacedTruth(const BaseMesh& base, const ReliefMap& map, double depth,
                 double texels_per_sheet_edge = 2.0, size_t max_sheet_triangles = size_t(1) << 21);
  ~DisplacedTruth();
  DisplacedTruth(const DisplacedTruth&) = delete;
  DisplacedTruth& operator=(const DisplacedTruth&) = delete;

  // First hit along origin + t direction (unit), t in [0, t_max].
  DisplacedHit intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_max) const;
  // Is the relief met for t in [t_min, t_max]? `from` (a hit's base_triangle), where the ray
  // starts at or under the sheet: the walk starts there, as Embree would not see it enter.
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min, double t_max,
                int from = -1) const;

  // Hits lie on the surface to double rounding; how far off the ray each is, it states itself.
  double tessellation_bound() const { return 0.0; }
  double vertical_bound() const { return 0.0; }
  double rounding_bound() const { return TruthSurface::kDoubleRounding; }
  int subdivision() const { return sheets_->subdivision(); }  // sheet triangles per base edge
  size_t triangles() const { return sheets_->triangles(); }
  double build_ms() const { return build_ms_; }
  uint64_t primary_rays() const { return primary_rays_.load(); }
  uint64_t shadow_rays() const { return shadow_rays_.load(); }
  // Work so far: Embree queries of the sheet and chords solved against the map.
  uint64_t embree_queries() const { return embree_queries_.load(); }
  uint64_t chords() const { return chords_.load(); }
  // Its two stages' geometry, for tests and benchmarks.
  const BasePrisms& prisms() const { return *prisms_; }
  const ShellSheets& sheets() const { return *sheets_; }

  // The chord tolerances, in texels of the prism the walk is in.
  static constexpr double kWalkDeviation = 1e-2;
  static constexpr double kHitDeviation = 1e-5;

 private:
  struct Chord;
  // The first t >= t_min at which the ray is at or below the relief, walking from prism `from`
  // while under the sheet; or, with `resume` set, where it left the sheet (NaN: the end).
  // `any_hit`: only whether it is met (a shadow ray), not where.
  DisplacedHit walk(const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max,
                    unsigned from, bool any_hit, double& resume) const;
  DisplacedHit first_hit(const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max,
                         int from, bool any_hit) const;
  // The first chord parameter in [0, 1] at or below the relief, texture space a to b, or NaN.
  double chord_crossing(const glm::dvec3& a, const glm::dvec3& b) const;
  // How far the chord's world image strays from the ray, at most (checked at 1/4, 1/2, 3/4).
  double chord_deviation(const glm::dvec3& o, const glm::dvec3& d, const PrismPoint& a,
                         const PrismPoint& b) const;
  glm::dvec3 texture_point(const PrismPoint& p) const;
  DisplacedHit resolve(const glm::dvec3& o, const glm::dvec3& d, const Chord& chord,
                       double deviation, int level) const;
  double lift(double deviation, double texel_world) const;
  double edge_crossing(const glm::dvec3& o, const glm::dvec3& d, int edge, const PrismPoint& a,
                       double t_in, const PrismPoint& b, double t_out, PrismPoint& at) const;
  DisplacedHit hit_at(const glm::dvec3& o, const glm::dvec3& d, const PrismPoint& p,
                      double off_ray) const;
  double least_depth(const glm::dvec2& lo, const glm::dvec2& hi) const;

  ReliefMap map_;  // a plain map's depths (no colour), or a meta-relief's layers alone
  std::unique_ptr<MetaReliefTruth> meta_;
  std::vector<MinPyramid> pyramids_;  // the least depths of the map, or of each layer
  double depth_ = 1;
  double max_slope_ = 0;  // the map's largest depth step between neighbouring texels (finest)
  std::unique_ptr<BasePrisms> prisms_;
  std::unique_ptr<ShellSheets> sheets_;
  double build_ms_ = 0;
  mutable ShardedCounter primary_rays_, shadow_rays_, embree_queries_, chords_;
};

}  // namespace rl
