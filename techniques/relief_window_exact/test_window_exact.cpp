// The window search's knobs trade time, never answers: every setting finds the default's hits.
#include <cmath>

#include <gtest/gtest.h>

#include "relief/heightfield_reference.h"
#include "relief/procedural.h"
#include "support/test_support.h"
#include "technique/technique.h"

namespace rl {
namespace {

// Rays whose hit (or miss) differs from `base` by more than 1e-4 in t and is not the
// double-precision reference's either (float rounding may part two exact searches on a graze).
int rays_off(const std::vector<ProbeHit>& h, const std::vector<ProbeHit>& base,
             const ReliefMap& map, const std::vector<ProbeRay>& rays) {
  int off = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    if (h[i].hit == base[i].hit && std::abs(h[i].t - base[i].t) <= 1e-4) continue;
    const glm::dvec3 o(rays[i].origin), d(rays[i].direction);
    const ReferenceHit ref = intersect_heightfield(map, o, d, 1.0 - o.z);
    off += !(h[i].hit == ref.hit && std::abs(h[i].t - ref.t) <= 1e-4);
  }
  return off;
}

// The most fetches a ray may take at `overrides`, by the technique's declared contract.
double fetch_bound(const ParamValues& overrides, const ReliefMap& map, const ProbeRay& ray) {
  const TechniqueRegistry& registry = TechniqueRegistry::instance();
  RayQuery q{.params = registry.resolve("relief_window_exact", overrides, "test"),
             .map_width = map.width,
             .map_height = map.height};
  q.span_texels = glm::abs(glm::dvec2(ray.direction)) * glm::dvec2(map.width, map.height);
  return registry.find("relief_window_exact")->info.contract.max_fetches(q);
}

// Each knob at its ends and between: the first level, how soon it climbs, one window for any
// way, and how many texels' cells a failed one-texel step solves (the ray is advanced to the
// bound's depth first, and a stretch that ends without a hit hands its last t back). On a
// random 512^2 map, where every cell is a feature, and on sines, at 5 and 45 degrees; every
// setting within the declared fetch bound (the contract suite checks the default only).
TEST(WindowExact, EverySettingFindsTheDefaultsHitsWithinItsFetchBound) {
  const std::pair<const char*, ReliefMap> maps[] = {
      {"random", test::random_map(512, 5)},
      {"sines", make_procedural("sines", 512, {}, 10.0, "test")}};
  const ParamValues settings[] = {
      {{"solve_texels", 1}}, {{"solve_texels", 3}},   {{"solve_texels", 16}},
      {{"start_level", 0}},  {{"start_level", 16}},   {{"climb_after", 1}},
      {{"climb_after", 4}},  {{"windows_by_way", 0}}, {{"windows_by_way", 0}, {"solve_texels", 1}}};
  for (const auto& [name, map] : maps) {
    for (double el : {5.0, 45.0}) {
      SCOPED_TRACE(std::string(name) + " at " + std::to_string(int(el)) + " deg");
      const std::vector<ProbeRay> rays =
          test::as_probe_rays(test::random_tangent_rays(512, el, el, 0.08, 13, -1e-4));
      const std::vector<ProbeHit> base = test::probe("relief_window_exact", {}, map, rays);
      for (const ParamValues& setting : settings) {
        const std::string label = testing::PrintToString(setting);
        const std::vector<ProbeHit> h = test::probe("relief_window_exact", setting, map, rays);
        EXPECT_EQ(rays_off(h, base, map, rays), 0) << label;
        int over = 0;
        for (size_t i = 0; i < rays.size(); ++i)
          over += h[i].fetches > fetch_bound(setting, map, rays[i]);
        EXPECT_EQ(over, 0) << label;
      }
    }
  }
}

}  // namespace
}  // namespace rl
