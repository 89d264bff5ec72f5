#include "relief/meta_relief.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/parallel.h"

namespace rl {
namespace {

// GL_LINEAR + GL_REPEAT over a single-channel map (an AO map).
double sample_scalar(const std::vector<float>& values, int width, int height, double u, double v) {
  const double x = u * width - 0.5, y = v * height - 0.5;
  const double fx0 = std::floor(x), fy0 = std::floor(y);
  const double fx = x - fx0, fy = y - fy0;
  auto at = [&](double xi, double yi) {
    long long xw = static_cast<long long>(xi) % width, yw = static_cast<long long>(yi) % height;
    if (xw < 0) xw += width;
    if (yw < 0) yw += height;
    return double(values[size_t(yw) * width + size_t(xw)]);
  };
  return (at(fx0, fy0) * (1 - fx) + at(fx0 + 1, fy0) * fx) * (1 - fy) +
         (at(fx0, fy0 + 1) * (1 - fx) + at(fx0 + 1, fy0 + 1) * fx) * fy;
}

// Calls texel(index, u, v) for every texel centre of a width x height map, rows in parallel.
template <typename Texel>
void for_each_texel_centre(int width, int height, Texel&& texel) {
  parallel_for(
      size_t(height),
      [&](size_t begin, size_t end) {
        for (size_t y = begin; y < end; ++y)
          for (int x = 0; x < width; ++x)
            texel(y * width + x, (x + 0.5) / width, (y + 0.5) / double(height));
      },
      8);
}

}  // namespace

MetaRelief::MetaRelief(std::vector<MetaLayer> layers) : layers_(std::move(layers)) {
  if (layers_.empty()) throw std::invalid_argument("a meta-relief needs at least one layer");
  for (size_t i = 0; i < layers_.size(); ++i) {
    const MetaLayer& l = layers_[i];
    const std::string which = "meta-relief layer " + std::to_string(i);
    if (!(l.tiling > 0) || !std::isfinite(l.tiling))
      throw std::invalid_argument(which + ": tiling must be positive and finite, got " +
                                  std::to_string(l.tiling));
    if (!(l.weight_normal >= 0) || !(l.weight_depth >= 0) || !std::isfinite(l.weight_normal) ||
        !std::isfinite(l.weight_depth))
      throw std::invalid_argument(which + ": weights must be finite and non-negative (Eqs. 1-2)");
    if (l.map.width < 1 || l.map.height < 1 || !l.map.layers.empty())
      throw std::invalid_argument(which + ": needs a heightfield map");
    sum_normal_ += l.weight_normal;
    sum_depth_ += l.weight_depth;
  }
  if (!(sum_normal_ > 0))
    throw std::invalid_argument(
        "the meta-relief's normal weights sum to zero (Eq. 1 divides by it)");
  if (!(sum_depth_ > 0))
    throw std::invalid_argument(
        "the meta-relief's depth weights sum to zero (Eq. 2 divides by it)");
  for (size_t i = 0; i < layers_.size(); ++i) {
    min_depth_ += depth_share(i) * layers_[i].map.min_depth();
    max_depth_ += depth_share(i) * layers_[i].map.max_depth();
  }
}

double MetaRelief::depth(double u, double v) const {
  double d = 0;
  for (size_t i = 0; i < layers_.size(); ++i) {
    const MetaLayer& l = layers_[i];
    d += depth_share(i) * l.map.sample_depth(u * l.tiling, v * l.tiling);
  }
  return d;
}

glm::dvec4 MetaRelief::relief(double u, double v) const {
  glm::dvec3 n(0);
  double d = 0;
  for (size_t i = 0; i < layers_.size(); ++i) {
    const MetaLayer& l = layers_[i];
    const glm::dvec4 texel = l.map.sample_relief(u * l.tiling, v * l.tiling);
    n += normal_share(i) * decode_normal(texel);
    d += depth_share(i) * texel.a;
  }
  const double len = glm::length(n);
  n = len > 0 ? n / len : glm::dvec3(0, 0, 1);
  return glm::dvec4(n * 0.5 + 0.5, d);
}

double MetaRelief::finest_texels() const {
  double m = 0;
  for (const MetaLayer& l : layers_)
    m = std::max({m, l.map.width * l.tiling, l.map.height * l.tiling});
  return m;
}

ReliefMap bake_meta_relief(const MetaRelief& meta, int width, int height, const ReliefMap* color) {
  ReliefMap out;
  out.name = meta.layers()[0].map.name + "+meta";
  out.width = width;
  out.height = height;
  out.relief.resize(size_t(width) * height);
  out.color.resize(out.relief.size());
  const ReliefMap& base = color ? *color : meta.layers()[0].map;
  for_each_texel_centre(width, height, [&](size_t i, double u, double v) {
    out.relief[i] = glm::vec4(meta.relief(u, v));
    out.color[i] = glm::vec4(base.sample_color(u, v));
  });
  return out;
}

double combined_ao(const MetaRelief& meta, const std::vector<std::vector<float>>& layer_ao,
                   double u, double v, AoCombine how) {
  double ao = 1;
  for (size_t i = 0; i < layer_ao.size(); ++i) {
    const MetaLayer& l = meta.layers()[i];
    const double a = std::clamp(
        sample_scalar(layer_ao[i], l.map.width, l.map.height, u * l.tiling, v * l.tiling), 0.0,
        1.0);
    ao = how == AoCombine::Product ? ao * a : std::min(ao, a);
  }
  return ao;
}

std::vector<float> combine_ao_maps(const MetaRelief& meta,
                                   const std::vector<std::vector<float>>& layer_ao, int width,
                                   int height, AoCombine how) {
  if (layer_ao.size() != meta.layers().size())
    throw std::invalid_argument("combine_ao_maps: one AO map per layer");
  std::vector<float> out(size_t(width) * height);
  for_each_texel_centre(width, height, [&](size_t t, double u, double v) {
    out[t] = float(combined_ao(meta, layer_ao, u, v, how));
  });
  return out;
}

}  // namespace rl
