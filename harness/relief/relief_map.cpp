#include "relief/relief_map.h"

#include <algorithm>
#include <cmath>

#include "core/hash.h"
#include "core/wrap.h"
#include "relief/image_backend.h"
#include "relief/meta_relief.h"

namespace rl {
namespace {

// GL_LINEAR footprint of coordinate u on n texels: texel i0, i0 + 1 and the weight of i0 + 1.
void linear_footprint(double u, int n, int& i0, int& i1, double& f) {
  double x = u * n - 0.5;
  double fl = std::floor(x);
  f = x - fl;
  i0 = wrap_index(static_cast<long>(fl), n);
  i1 = wrap_index(i0 + 1, n);
}

// GL_LINEAR + GL_REPEAT over a w x h grid of texels that get(x, y) reads.
template <typename Get>
glm::dvec4 bilinear(int w, int h, double u, double v, Get get) {
  int x0, x1, y0, y1;
  double fx, fy;
  linear_footprint(u, w, x0, x1, fx);
  linear_footprint(v, h, y0, y1, fy);
  glm::dvec4 a = get(x0, y0), b = get(x1, y0), c = get(x0, y1), d = get(x1, y1);
  return (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy;
}

}  // namespace

size_t ReliefMap::index(int x, int y) const {
  return static_cast<size_t>(wrap_index(y, height)) * width + size_t(wrap_index(x, width));
}

double ReliefMap::sample_depth(double u, double v) const {
  return sample_relief(u, v).a;
}

glm::dvec4 ReliefMap::sample_relief(double u, double v) const {
  return bilinear(width, height, u, v,
                  [&](int x, int y) { return glm::dvec4(relief[index(x, y)]); });
}

glm::dvec4 ReliefMap::sample_relief_clamped(double u, double v) const {
  // Between the edge texels' centres GL_LINEAR never reaches the other side, so the repeating
  // sampler gives the clamped answer there.
  return sample_relief(std::clamp(u, 0.5 / width, 1.0 - 0.5 / width),
                       std::clamp(v, 0.5 / height, 1.0 - 0.5 / height));
}

double ReliefMap::surface_depth(double u, double v) const {
  return meta ? meta->depth(u, v) : sample_depth(u, v);
}

glm::dvec4 ReliefMap::surface_relief(double u, double v) const {
  return meta ? meta->relief(u, v) : sample_relief(u, v);
}

glm::dvec4 ReliefMap::sample_color(double u, double v) const {
  const int w = color_w();
  return bilinear(w, color_h(), u, v,
                  [&](int x, int y) { return glm::dvec4(color[size_t(y) * w + size_t(x)]); });
}

float ReliefMap::min_depth() const {
  float m = 1;
  for (const auto& t : relief) m = std::min(m, t.a);
  return m;
}

std::vector<float> ReliefMap::depths() const {
  std::vector<float> d(relief.size());
  for (size_t i = 0; i < d.size(); ++i) d[i] = relief[i].a;
  return d;
}

float ReliefMap::max_depth() const {
  float m = 0;
  for (const auto& t : relief) m = std::max(m, t.a);
  return m;
}

uint64_t ReliefMap::content_hash() const {
  uint64_t h = fnv1a64(&width, sizeof width);
  h = fnv1a64(&height, sizeof height, h);
  h = fnv1a64(relief.data(), relief.size() * sizeof(glm::vec4), h);
  h = fnv1a64(color.data(), color.size() * sizeof(glm::vec4), h);
  if (color_width > 0) {  // only then, so maps without their own colour size keep their hash
    h = fnv1a64(&color_width, sizeof color_width, h);
    h = fnv1a64(&color_height, sizeof color_height, h);
  }
  if (layers.empty()) return h;
  h = fnv1a64(&layers.count, sizeof layers.count, h);
  h = fnv1a64(layers.depth.data(), layers.depth.size() * sizeof(float), h);
  h = fnv1a64(layers.normal.data(), layers.normal.size() * sizeof(glm::vec3), h);
  return fnv1a64(layers.color.data(), layers.color.size() * sizeof(glm::vec3), h);
}

int LayerStack::used(size_t texel) const {
  const size_t texels = count ? depth.size() / count : 0;
  int n = 0;
  for (int l = 0; l < count; ++l) n += depth[l * texels + texel] < 1.0f;
  return n;
}

size_t ReliefMap::gpu_bytes(bool meta_layers) const {
  size_t texel = quantized ? 4 : 16;
  const size_t ambient = ambient_visibility.empty() ? 0 : (quantized ? 1 : 4);
  size_t bytes = static_cast<size_t>(width) * height * (texel + ambient) +
                 static_cast<size_t>(color_w()) * color_h() * texel;
  if (meta_layers && meta) {
    bytes -= static_cast<size_t>(width) * height * texel;  // the bake is not sampled
    for (const MetaLayer& l : meta->layers()) bytes += size_t(l.map.width) * l.map.height * texel;
    if (!meta_ambient_visibility.empty()) {  // nor the combined AO map: the layers' are
      bytes -= static_cast<size_t>(width) * height * ambient;
      for (const MetaLayer& l : meta->layers())
        bytes += size_t(l.map.width) * l.map.height * ambient;
    }
  }
  return bytes;
}

glm::vec3 layer_normal_from_xy(float x, float y, int layer) {
  const float z = std::sqrt(std::max(0.0f, 1.0f - (x * x + y * y)));
  return {x, y, layer % 2 ? -z : z};
}

glm::dvec3 decode_normal(const glm::dvec4& rgba) {
  glm::dvec3 n = glm::dvec3(rgba) * 2.0 - 1.0;
  double len = glm::length(n);
  return len > 0 ? n / len : glm::dvec3(0, 0, 1);
}

void quantize_8bit(ReliefMap& map) {
  auto q = [](float v) { return std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f; };
  for (auto& t : map.relief) t = glm::vec4(q(t.r), q(t.g), q(t.b), q(t.a));
  for (auto& c : map.color) c = glm::vec4(q(c.r), q(c.g), q(c.b), 1.0f);
  LayerStack& layers = map.layers;
  const size_t texels = size_t(map.width) * map.height;
  double angle_sum = 0, angle_max = 0;
  long surface = 0;
  for (size_t k = 0; k < layers.depth.size(); ++k) {
    const bool on_surface = layers.depth[k] < 1.0f;  // depth 1: no surface on this layer here
    layers.depth[k] = q(layers.depth[k]);
    // Stored as the paper does: x and y in 8 bits each, z rebuilt with the layer's sign.
    const glm::vec3 n = layers.normal[k];
    layers.normal[k] = layer_normal_from_xy(q(n.x * 0.5f + 0.5f) * 2.0f - 1.0f,
                                            q(n.y * 0.5f + 0.5f) * 2.0f - 1.0f, int(k / texels));
    if (on_surface && glm::length(n) > 0) {
      const double cos_angle =
          glm::dot(glm::normalize(glm::dvec3(n)), glm::normalize(glm::dvec3(layers.normal[k])));
      const double deg = std::acos(std::clamp(cos_angle, -1.0, 1.0)) * 180.0 / M_PI;
      angle_sum += deg;
      angle_max = std::max(angle_max, deg);
      ++surface;
    }
    const glm::vec3 c = layers.color[k];
    layers.color[k] = glm::vec3(q(c.r), q(c.g), q(c.b));
  }
  if (surface > 0) {
    layers.normal_storage_err_mean_deg = angle_sum / double(surface);
    layers.normal_storage_err_max_deg = angle_max;
  }
  map.quantized = true;
}

ReliefMap resample(const ReliefMap& map, int width, int height) {
  if (width == map.width && height == map.height) return map;
  auto resize = [&](const std::vector<glm::vec4>& src) {
    std::vector<glm::vec4> dst(static_cast<size_t>(width) * height);
    image_backend().resize(&src[0].x, map.width, map.height, 4, &dst[0].x, width, height);
    return dst;
  };
  ReliefMap out;
  out.name = map.name;
  out.width = width;
  out.height = height;
  out.relief = resize(map.relief);
  // A colour map of its own size keeps it (Section 4.3's independent resolutions).
  out.color = map.color_width > 0 ? map.color : resize(map.color);
  out.color_width = map.color_width;
  out.color_height = map.color_height;
  for (auto& t : out.relief) {
    glm::dvec3 n = decode_normal(glm::dvec4(t));
    t = glm::vec4(glm::vec3(n * 0.5 + 0.5), std::clamp(t.a, 0.0f, 1.0f));
  }
  for (auto& c : out.color) c = glm::clamp(c, glm::vec4(0), glm::vec4(1));
  out.quantized = false;
  return out;
}

void normals_from_depth(ReliefMap& map, double depth_per_texel) {
  std::vector<glm::vec4> out(map.relief.size());
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      // Surface height is -depth; its normal is (depth_x, depth_y, 1) in slope units.
      double dx = 0.5 * (map.depth_texel(x + 1, y) - map.depth_texel(x - 1, y));
      double dy = 0.5 * (map.depth_texel(x, y + 1) - map.depth_texel(x, y - 1));
      glm::dvec3 n = glm::normalize(glm::dvec3(dx * depth_per_texel, dy * depth_per_texel, 1));
      out[map.index(x, y)] = glm::vec4(glm::vec3(n * 0.5 + 0.5), map.depth_texel(x, y));
    }
  }
  map.relief = std::move(out);
  map.quantized = false;
}

}  // namespace rl
