// The technique contract: every registered technique -- one dropped into techniques/ tomorrow
// included, with no edit here -- held to what its describe() declares (technique/contract.h).
// Each clause is one test per technique, named Registry/Contract.<Clause>/<technique>, so a
// failure says which plugin broke which promise. The cases are in contract_cases.h.
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <optional>
#include <sstream>

#include <gtest/gtest.h>

#include "contract/contract_cases.h"
#include "relief/heightfield_reference.h"

namespace rl::contract {
namespace {

// --- Thresholds, each with why. ---

// Exact answers: within this many texels of the closed-form hit (the figure), and the
// same hit/miss, but for rays whose reference hit is within kTieDepth of the floor (a ray that
// reaches depth 1 exactly on an empty texel hits or misses on float rounding).
constexpr double kExactTexels = 0.05;
constexpr double kTieDepth = 1e-4;
// A converging search at its finest setting: within its stated t error, GL_LINEAR's filtering
// and this many texels of float rounding.
constexpr double kConvergedTexels = 0.05;
// Without a stated accuracy, a converging search at its finest setting is within this many
// texels of the reference on smooth maps.
constexpr double kConvergedUnstatedTexels = 0.5;
// Raising an accuracy knob must not make the mean error grow by more than this share (and
// this many texels of noise): a search that gets worse as it is given more work is broken.
constexpr double kLadderSlack = 0.05, kLadderNoiseTexels = 0.02;
// A probe of a pixel's ray lands within this many texels of the frame's hit at that pixel (plus
// one step of a stepping search).
constexpr double kFrameAgreementTexels = 0.5;
// A probe disagreement (hit against miss) counts this many texels in the ladder's mean.
constexpr double kMismatchTexels = 64;

// --- Which technique meets which case: decided by what it declares. ---

// A ray search on a single heightfield map (cell complexes and heightfield objects read other
// maps; a rasteriser has no ray to probe).
bool probes_heightfields(const TechniqueInfo& info) {
  return info.contract.ray_probe && info.draws.reads.has(Representation::Heightfield);
}

// Rays that start inside the depth range are its to answer when it draws a box proxy's sides
// or an impostor.
std::vector<ProbeRay> rays_for(const TechniqueInfo& info) {
  return hard_rays(info.draws.proxies.has(Proxy::Box) ||
                   info.draws.reads.has(Representation::Impostor));
}

bool searches(const TechniqueInfo& info) {
  return info.contract.answer == Answer::Exact || info.contract.answer == Answer::Converging;
}

std::vector<size_t> drawable_cases(const TechniqueInfo& info) {
  std::vector<size_t> out;
  for (size_t i = 0; i < render_cases().size(); ++i)
    if (cannot_render(info, render_cases()[i].scene).empty()) out.push_back(i);
  return out;
}

ParamValues finest(const std::string& technique) {
  return settings(technique, info_of(technique).contract.finest);
}

// Its defaults, and its finest setting where that differs.
std::vector<ParamValues> default_and_finest(const std::string& technique) {
  std::vector<ParamValues> out = {settings(technique)};
  if (finest(technique) != out[0]) out.push_back(finest(technique));
  return out;
}

bool finite(glm::vec4 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

double wrapped(double a) {
  return a - std::floor(a);
}

// Where a probe hit lies against the ray, in texels: the hit's (u, v) against the ray's point
// at the hit's t (modulo the tiling).
double off_the_ray_texels(const ReliefMap& map, const ProbeRay& ray, const ProbeHit& h) {
  const glm::dvec3 p = glm::dvec3(ray.origin) + double(h.t) * glm::dvec3(ray.direction);
  const double du = wrapped(p.x - h.uv.x + 0.5) - 0.5, dv = wrapped(p.y - h.uv.y + 0.5) - 0.5;
  return std::hypot(du * map.width, dv * map.height);
}

// How far along the ray, in texels, a probe hit is from the reference; kMismatchTexels when
// one hits and the other does not (a floor tie counts as agreement).
double probe_error_texels(const ReliefMap& map, const ProbeRay& ray, const ProbeHit& h,
                          const ReferenceAnswer& ref) {
  auto error = [&](bool hit, double t) {
    if (h.hit != hit) {
      const double depth = ray.origin.z + (hit ? t : h.t);
      return depth >= 1 - kTieDepth ? 0 : kMismatchTexels;
    }
    if (!hit) return 0.0;
    return texel_distance(map, glm::dvec3(0), glm::dvec3(ray.direction) * (double(h.t) - t));
  };
  return std::min(error(ref.hit, ref.t), error(ref.other_hit, ref.other_t));
}

// The stated accuracy along one ray, in texels: its t error, and GL_LINEAR's filtering near
// the crossing (llvmpipe rounds the weights to 8 bits) carried along the ray, + kConvergedTexels.
double converged_tolerance_texels(const TechniqueContract& c, const ParamValues& params,
                                  const ReliefMap& map, const ProbeRay& ray,
                                  const ReferenceAnswer& ref) {
  if (!c.t_error) return kConvergedUnstatedTexels;
  const double ray_texels_per_t = texel_distance(map, glm::dvec3(0), glm::dvec3(ray.direction));
  const glm::dvec3 at = glm::dvec3(ray.origin) + ref.t * glm::dvec3(ray.direction);
  const double filtering =
      ref.hit ? depth_error_along_ray(map, ray, ref.t, filtering_tolerance_at(map, at.x, at.y)) : 0;
  return (c.t_error(ray_query(params, map, ray)) + filtering) * ray_texels_per_t + kConvergedTexels;
}

// A ray and both answers, for a failure message.
std::string describe(const ProbeRay& ray, const ProbeHit& h, const ReferenceAnswer& ref) {
  std::ostringstream s;
  s << " (origin " << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << "; direction "
    << ray.direction.x << ", " << ray.direction.y << ", 1; technique "
    << (h.hit ? "t = " + std::to_string(h.t) : std::string("miss")) << ", reference "
    << (ref.hit ? "t = " + std::to_string(ref.t) : std::string("miss")) << ")";
  return s.str();
}

// One suite per kind of promise, instantiated over the techniques that declare it (so a clause
// that does not apply is not a skipped test, and no test names a technique).
class Contract : public ::testing::TestWithParam<std::string> {
 protected:
  const std::string& name() const { return GetParam(); }
  const TechniqueInfo& info() const { return info_of(name()); }
  const TechniqueContract& contract() const { return info().contract; }
};
class ExactContract : public Contract {};             // answer: exact
class ConvergingContract : public Contract {};        // answer: converging
class ConvergingSearchContract : public Contract {};  // ... with a heightfield ray search
class SearchContract : public Contract {};            // exact or converging heightfield search
class ProbeContract : public Contract {};             // a heightfield ray search of any answer

std::vector<std::string> names_where(const std::function<bool(const TechniqueInfo&)>& keep) {
  std::vector<std::string> out;
  for (const std::string& name : technique_names())
    if (keep(info_of(name))) out.push_back(name);
  return out;
}

// --- Fetches. ---

TEST_P(Contract, FetchesNeverExceedTheDeclaredBound) {
  const TechniqueContract& c = contract();
  double worst_ratio = 0;
  std::string worst;
  auto note = [&](double measured, double bound, const std::string& where) {
    EXPECT_LE(measured, bound) << name() << " fetched " << measured << " > its bound " << bound
                               << " (" << c.max_fetches_formula << ") on " << where;
    if (bound > 0 && measured / bound > worst_ratio) {
      worst_ratio = measured / bound;
      worst = std::to_string(int(measured)) + " of " + std::to_string(int(bound)) + " on " + where;
    }
  };
  for (const ParamValues& params : default_and_finest(name())) {
    if (probes_heightfields(info()))
      for (const ProbeMap& m : probe_maps()) {
        const std::vector<ProbeRay> rays = rays_for(info());
        const std::vector<ProbeHit> hits = probe(name(), params, m.map, rays);
        for (size_t i = 0; i < rays.size(); ++i)
          note(hits[i].fetches, c.max_fetches(ray_query(params, m.map, rays[i])),
               "probe map " + m.name + " ray " + std::to_string(i));
      }
    for (size_t k : drawable_cases(info())) {
      const Frame f = render(k, name(), params);
      // Every fragment any pass shaded, kept or discarded, and every pixel written.
      double most = 0;
      for (size_t i = 0; i < f.image.size(); ++i)
        most = std::max({most, double(f.image.hit[i].w), double(f.counts.fetch_max[i])});
      note(most, c.max_fetches(f.query), "frame " + render_cases()[k].name);
    }
  }
  std::cout << "[contract] " << name() << " fetches: worst " << worst << " (bound "
            << c.max_fetches_formula << ")\n";
}

// --- Finite output. ---

TEST_P(Contract, OutputsAreFinite) {
  for (const ParamValues& params : default_and_finest(name())) {
    if (probes_heightfields(info()))
      for (const ProbeMap& m : probe_maps()) {
        const std::vector<ProbeRay> rays = rays_for(info());
        const std::vector<ProbeHit> hits = probe(name(), params, m.map, rays);
        for (size_t i = 0; i < hits.size(); ++i)
          ASSERT_TRUE(std::isfinite(hits[i].t) && std::isfinite(hits[i].uv.x) &&
                      std::isfinite(hits[i].uv.y) && std::isfinite(hits[i].depth))
              << name() << " probe on " << m.name << " ray " << i;
      }
    for (size_t k : drawable_cases(info())) {
      const Frame f = render(k, name(), params);
      for (size_t i = 0; i < f.image.size(); ++i)
        ASSERT_TRUE(finite(f.image.color[i]) && finite(f.image.position[i]) &&
                    finite(f.image.normal[i]) && finite(f.image.hit[i]) && finite(f.image.aux[i]))
            << name() << " pixel " << i << " of " << render_cases()[k].name;
      EXPECT_EQ(f.metrics.at("nonfinite_px"), 0) << render_cases()[k].name;
    }
  }
}

// --- Op counts (the GPU cost model's input). ---

TEST_P(Contract, EveryShadedFragmentCountsItsOps) {
  const ParamValues params = settings(name());
  for (size_t k : drawable_cases(info())) {
    const Frame f = render(k, name(), params);
    const PixelOpCounts ops = count_ops(k, name(), params);
    // The same passes draw the same fragments: each must write its counts, so a pass that
    // forgot would leave its pixels unpriced by the cost model.
    size_t shaded = 0;
    for (size_t i = 0; i < ops.fragments.size(); ++i) {
      ASSERT_EQ(ops.fragments[i], f.counts.fragments[i])
          << name() << " pixel " << i << " of " << render_cases()[k].name;
      if (!ops.fragments[i]) continue;
      ++shaded;
      EXPECT_GT(ops.ops[int(OpKind::Float)][i], 0u) << name() << " pixel " << i;
    }
    EXPECT_GT(shaded, 0u) << render_cases()[k].name;
  }
}

// --- What a row was drawn with (run/cell_provenance.h). ---

// A run names the programs a row was drawn with from what its frames request of the shader
// library; a technique that kept a program from an earlier frame would draw later cells with
// programs no row names, and an edited shader would leave those rows standing.
TEST_P(Contract, EveryFrameRequestsItsPrograms) {
  const ParamValues params = settings(name());
  for (size_t k : drawable_cases(info())) {
    const auto [first, second] = programs_of_two_frames(k, name(), params);
    EXPECT_FALSE(first.empty()) << render_cases()[k].name;
    EXPECT_EQ(first, second) << name() << " on " << render_cases()[k].name;
  }
}

// --- Exact answers. ---

TEST_P(ExactContract, ExactHitsMatchTheClosedForm) {
  const ParamValues params = settings(name());
  if (probes_heightfields(info()))
    for (const ProbeMap& m : probe_maps()) {
      const std::vector<ProbeRay> rays = rays_for(info());
      const std::vector<ProbeHit> hits = probe(name(), params, m.map, rays);
      double worst = 0;
      for (size_t i = 0; i < rays.size(); ++i) {
        const double e = probe_error_texels(m.map, rays[i], hits[i],
                                            reference(m.map, rays[i], contract().surface));
        EXPECT_LE(e, kExactTexels)
            << name() << " on " << m.name << " ray " << i << (hits[i].hit ? " hit" : " missed");
        worst = std::max(worst, e);
      }
      std::cout << "[contract] " << name() << " on " << m.name << ": worst " << worst
                << " texels\n";
    }
  // Whole frames against a truth of the surface it answers on: every covered pixel's position
  // within kExactTexels.
  for (size_t k : drawable_cases(info())) {
    const RenderCase& rc = render_cases()[k];
    if (!(probes_heightfields(info()) ? rc.truth_is_the_map : rc.truth_is_the_source_mesh))
      continue;
    const Frame f = render(k, name(), params);
    std::cout << "[contract] " << name() << " frame " << render_cases()[k].name << ": wrong "
              << f.metrics.at("wrong_pct") << "%, position max "
              << f.metrics.at("pos_err_texels_max") << " texels\n";
    if (f.metrics.truth_flagged()) continue;
    EXPECT_LE(f.metrics.at("pos_err_texels_max"), kExactTexels) << rc.name;
    // Hit and miss agree but for at most one pixel (a rasteriser's edge rule).
    EXPECT_LE(f.metrics.at("missed_pct") + f.metrics.at("false_pct"),
              100.0 / std::max(1.0, f.metrics.at("union_px")) + 1e-9)
        << rc.name;
  }
}

// --- Converging answers. ---

// The stated accuracy's condition holds on this ray at `params`: its first crossing leads into
// a stretch inside the relief no shorter than what the search may step over.
bool resolvable(const TechniqueContract& c, const ParamValues& params, const ReliefMap& map,
                const ProbeRay& ray, const ReferenceAnswer& ref) {
  if (!ref.hit || !c.t_resolution) return true;
  const double step = c.t_resolution(ray_query(params, map, ray));
  return inside_stretch(map, c.surface, ray, ref.t, step) >= step;
}

// Mean probe error (texels) over the smooth maps and the hard rays resolvable at `coarsest`.
double mean_probe_error(const std::string& technique, const ParamValues& params,
                        const ParamValues& coarsest) {
  const TechniqueInfo& info = info_of(technique);
  double sum = 0;
  long n = 0;
  for (const ProbeMap& m : probe_maps()) {
    if (!m.smooth) continue;
    const std::vector<ProbeRay> rays = rays_for(info);
    const std::vector<ProbeHit> hits = probe(technique, params, m.map, rays);
    for (size_t i = 0; i < rays.size(); ++i) {
      const ReferenceAnswer ref = reference(m.map, rays[i], info.contract.surface);
      if (!resolvable(info.contract, coarsest, m.map, rays[i], ref)) continue;
      sum += probe_error_texels(m.map, rays[i], hits[i], ref);
      ++n;
    }
  }
  return sum / std::max(n, 1L);
}

// Mean frame error over the cases it draws: the wrong pixels' share in texels of a kMismatch
// each, plus the covered pixels' mean position error.
double mean_frame_error(const std::string& technique, const ParamValues& params) {
  double sum = 0;
  int n = 0;
  for (size_t k : drawable_cases(info_of(technique))) {
    const Frame f = render(k, technique, params);
    sum += f.metrics.at("wrong_pct") / 100 * kMismatchTexels + f.metrics.at("pos_err_texels_mean");
    ++n;
  }
  return sum / std::max(n, 1);
}

TEST_P(ConvergingSearchContract, ConvergingIsAccurateAtItsFinestSetting) {
  const TechniqueContract& c = contract();
  const ParamValues params = finest(name());
  for (const ProbeMap& m : probe_maps()) {
    if (!m.smooth) continue;
    const std::vector<ProbeRay> rays = rays_for(info());
    const std::vector<ProbeHit> hits = probe(name(), params, m.map, rays);
    double worst = 0;
    int thin = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      const ReferenceAnswer ref = reference(m.map, rays[i], c.surface);
      if (!resolvable(c, params, m.map, rays[i], ref)) {
        ++thin;
        continue;
      }
      const double e = probe_error_texels(m.map, rays[i], hits[i], ref);
      EXPECT_LE(e, converged_tolerance_texels(c, params, m.map, rays[i], ref))
          << name() << " on " << m.name << " ray " << i << describe(rays[i], hits[i], ref);
      worst = std::max(worst, e);
    }
    std::cout << "[contract] " << name() << " finest on " << m.name << ": worst " << worst
              << " texels (" << thin << " rays graze a stretch thinner than a step)\n";
  }
}

// The next value of a knob's ladder towards `to`: doubled (halved for a knob where smaller is
// finer), whole numbers kept whole; a bool goes straight to its finest value.
double next_rung(double v, double to, bool larger_is_finer) {
  if (larger_is_finer) return std::min(to, std::max(v * 2, v + 1));
  const double half = std::floor(v / 2);
  return half <= to || v <= 1 ? to : half;
}

// Each knob from its default to its finest value, doubling (halving for a level of detail),
// the other knobs at their finest: the mean error never grows.
TEST_P(ConvergingContract, ConvergingNeverGetsWorseAsAKnobIsRaised) {
  const TechniqueContract& c = contract();
  const bool probe_based = probes_heightfields(info());
  for (const AccuracyKnob& knob : c.knobs) {
    const double from = settings(name()).at(knob.param), to = c.finest.at(knob.param);
    std::ostringstream ladder;
    double previous = INFINITY;
    std::optional<ParamValues> coarsest;  // the first rung: the rays it resolves are scored
    for (double v = from;; v = next_rung(v, to, knob.larger_is_finer)) {
      ParamValues p = c.finest;
      p[knob.param] = v;
      // The other knobs at their finest, or at their defaults where validate() refuses that.
      std::optional<ParamValues> params = valid_settings(name(), p);
      if (!params) params = valid_settings(name(), {{knob.param, v}});
      ASSERT_TRUE(params) << name() << ": " << knob.param << " = " << v << " is refused";
      if (!coarsest) coarsest = params;
      const double e = probe_based ? mean_probe_error(name(), *params, *coarsest)
                                   : mean_frame_error(name(), *params);
      ladder << " " << v << ":" << e;
      EXPECT_LE(e, previous * (1 + kLadderSlack) + kLadderNoiseTexels)
          << name() << " got worse as " << knob.param << " reached " << v;
      previous = e;
      if (v == to) break;
    }
    std::cout << "[contract] " << name() << " " << knob.param
              << " ladder (mean texels):" << ladder.str() << "\n";
  }
}

// --- Hits on the surface. ---

TEST_P(SearchContract, HitsLieOnTheRayAndNeverAboveTheSurface) {
  const TechniqueContract& c = contract();
  const ParamValues params = c.answer == Answer::Converging ? finest(name()) : settings(name());
  for (const ProbeMap& m : probe_maps()) {
    const std::vector<ProbeRay> rays = rays_for(info());
    const std::vector<ProbeHit> hits = probe(name(), params, m.map, rays);
    const double tolerance = filtering_tolerance(m.map) + 1e-4;
    for (size_t i = 0; i < rays.size(); ++i) {
      const ProbeHit& h = hits[i];
      if (!h.hit) continue;
      EXPECT_LE(off_the_ray_texels(m.map, rays[i], h), kExactTexels)
          << name() << " on " << m.name << " ray " << i << ": the hit is off its ray";
      const double t_tolerance = c.t_error ? c.t_error(ray_query(params, m.map, rays[i])) : 0;
      const ReferenceAnswer ref = reference(m.map, rays[i], c.surface);
      if (rays[i].origin.z > 0 && ref.hit && ref.t == 0) {
        // It starts inside the solid: the hit is the box's side, where the ray enters.
        EXPECT_LE(h.t, t_tolerance + 1e-4) << name() << " on " << m.name << " ray " << i
                                           << ": a ray starting inside hits where it starts";
        continue;
      }
      const double above = surface_depth(m.map, c.surface, h.uv.x, h.uv.y) - h.depth;
      if (c.hits_from_inside) {
        EXPECT_LE(above, tolerance)
            << name() << " on " << m.name << " ray " << i << ": the hit is above the surface";
      } else {
        // Within its stated error along t of a crossing: the gap to the surface grows no faster
        // than the ray's depth plus the surface's steepest change along the ray.
        const double lateral = glm::length(glm::dvec2(rays[i].direction));
        EXPECT_LE(std::abs(above), tolerance + t_tolerance * (1 + steepest_slope(m.map) * lateral))
            << name() << " on " << m.name << " ray " << i << ": the hit is off the surface";
      }
      EXPECT_LE(h.depth, 1 + 1e-4) << name() << " on " << m.name << " ray " << i;
    }
  }
}

// --- Every parameter does something. ---

// Everything a setting produces, stage by stage: stage 0 its probe answers on straight and
// curved rays (if it probes), stage 1 + k the G-buffer and frame columns of its k-th drawable
// case. Compared lazily, cheapest first: most parameters show in the probe.
std::vector<double> output_stage(const std::string& technique, const ParamValues& params,
                                 size_t stage) {
  std::vector<double> out;
  const TechniqueInfo& info = info_of(technique);
  if (stage == 0) {
    if (!probes_heightfields(info)) return out;
    std::vector<ProbeRay> rays = hard_rays(info.draws.proxies.has(Proxy::Box) ||
                                           info.draws.reads.has(Representation::Impostor));
    const std::vector<ProbeRay> curved = curved_rays();
    rays.insert(rays.end(), curved.begin(), curved.end());
    for (const ProbeHit& h : probe(technique, params, probe_maps()[3].map, rays))
      out.insert(out.end(), {h.t, h.uv.x, h.uv.y, h.depth, double(h.hit), double(h.fetches)});
    return out;
  }
  const Frame f = render(drawable_cases(info).at(stage - 1), technique, params);
  for (size_t i = 0; i < f.image.size(); ++i)
    for (const glm::vec4& v :
         {f.image.color[i], f.image.position[i], f.image.normal[i], f.image.hit[i]})
      out.insert(out.end(), {v.x, v.y, v.z, v.w});
  for (const auto& [column, value] : f.columns) out.push_back(value);
  return out;
}

TEST_P(Contract, EveryParameterChangesSomething) {
  const ParamValues defaults = settings(name());
  const size_t stages = 1 + drawable_cases(info()).size();
  std::vector<std::optional<std::vector<double>>> base(stages);
  auto differs = [&](const ParamValues& params) {
    for (size_t k = 0; k < stages; ++k) {
      if (!base[k]) base[k] = output_stage(name(), defaults, k);
      if (output_stage(name(), params, k) != *base[k]) return true;
    }
    return false;
  };
  for (const ParamSpec& p : info().params) {
    const double def = defaults.at(p.name);
    // The least value, one just above it, or the greatest (the other value of a bool) changes
    // some output; the cheap ends first (a precompute grows with most parameters).
    const double near_min = p.kind == ParamKind::Float
                                ? p.min_value + (p.max_value - p.min_value) / 4
                                : std::min(p.min_value + 1, p.max_value);
    bool changed = false;
    for (double other : {p.min_value, near_min, p.max_value}) {
      if (other == def || changed) continue;
      const std::optional<ParamValues> params = valid_settings(name(), {{p.name, other}});
      changed = params && differs(*params);
    }
    EXPECT_TRUE(changed) << name() << ": no value of " << p.name << "'s range [" << p.min_value
                         << ", " << p.max_value << "] (default " << def
                         << ") changes anything it outputs";
  }
}

// --- The probe and the frame run one search. ---

// The probe of each pixel's ray against that pixel of the frame: the same answer up to one step
// of the search (the CPU's pixel ray and the rasterised one differ by float rounding, which at a
// feature's edge may move a stepping search by a step), and half a texel.
double frame_tolerance_texels(const TechniqueContract& c, const ParamValues& params,
                              const ReliefMap& map, const ProbeRay& ray) {
  if (!c.t_resolution) return kFrameAgreementTexels;
  const double ray_texels_per_t = texel_distance(map, glm::dvec3(0), glm::dvec3(ray.direction));
  return kFrameAgreementTexels + c.t_resolution(ray_query(params, map, ray)) * ray_texels_per_t;
}

TEST_P(ProbeContract, ProbesAgreeWithTheFrameAndTheReference) {
  const TechniqueContract& c = contract();
  const ParamValues params = settings(name());
  for (size_t k : drawable_cases(info())) {
    const RenderCase& rc = render_cases()[k];
    if (!rc.planar_rays) continue;
    const Frame f = render(k, name(), params);
    const std::vector<ProbeHit> hits = probe(name(), params, *f.map, f.pixel_rays, f.depth_aspect);
    long compared = 0, disagree = 0;
    for (size_t i = 0; i < hits.size(); ++i) {
      if (f.pixel_rays[i].origin.z != 0 || !f.image.covered(i)) continue;  // not the relief
      ++compared;
      const glm::dvec2 d(wrapped(hits[i].uv.x - f.image.hit[i].x + 0.5) - 0.5,
                         wrapped(hits[i].uv.y - f.image.hit[i].y + 0.5) - 0.5);
      const double apart = glm::length(d * glm::dvec2(f.map->width, f.map->height));
      const ReferenceAnswer ref = reference(*f.map, f.pixel_rays[i], c.surface);
      const bool floor_tie = !hits[i].hit && ref.hit && ref.t >= 1 - kTieDepth;
      if (!floor_tie &&
          (!hits[i].hit || apart > frame_tolerance_texels(c, params, *f.map, f.pixel_rays[i])))
        ++disagree;
      // An exact answer is the reference's on the pixel's own ray too.
      if (c.answer == Answer::Exact && rc.truth_is_the_map) {
        EXPECT_LE(probe_error_texels(*f.map, f.pixel_rays[i], hits[i], ref), kExactTexels)
            << name() << " on " << rc.name << " pixel " << i;
      }
    }
    std::cout << "[contract] " << name() << " probe vs frame on " << rc.name << ": " << disagree
              << " of " << compared << " pixels differ\n";
    EXPECT_GT(compared, 0) << rc.name;
    EXPECT_EQ(disagree, 0) << name() << " on " << rc.name;
  }
}

std::string technique_name(const ::testing::TestParamInfo<std::string>& i) {
  return i.param;
}

INSTANTIATE_TEST_SUITE_P(Registry, Contract, ::testing::ValuesIn(technique_names()),
                         technique_name);
INSTANTIATE_TEST_SUITE_P(Registry, ExactContract,
                         ::testing::ValuesIn(names_where([](const TechniqueInfo& i) {
                           return i.contract.answer == Answer::Exact;
                         })),
                         technique_name);
INSTANTIATE_TEST_SUITE_P(Registry, ConvergingContract,
                         ::testing::ValuesIn(names_where([](const TechniqueInfo& i) {
                           return i.contract.answer == Answer::Converging;
                         })),
                         technique_name);
INSTANTIATE_TEST_SUITE_P(Registry, ConvergingSearchContract,
                         ::testing::ValuesIn(names_where([](const TechniqueInfo& i) {
                           return i.contract.answer == Answer::Converging && probes_heightfields(i);
                         })),
                         technique_name);
INSTANTIATE_TEST_SUITE_P(Registry, SearchContract,
                         ::testing::ValuesIn(names_where([](const TechniqueInfo& i) {
                           return searches(i) && probes_heightfields(i);
                         })),
                         technique_name);
INSTANTIATE_TEST_SUITE_P(Registry, ProbeContract,
                         ::testing::ValuesIn(names_where(probes_heightfields)), technique_name);
// A registry without, say, an exact technique leaves a suite empty: that is not an error.
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ExactContract);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ConvergingContract);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ConvergingSearchContract);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(SearchContract);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ProbeContract);

}  // namespace
}  // namespace rl::contract
