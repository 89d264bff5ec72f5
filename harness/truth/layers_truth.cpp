#include "truth/layers_truth.h"

#include <cmath>
#include <stdexcept>

#include "core/grid_walk.h"

namespace rl {

LayersTruth::LayersTruth(const ReliefMap& map, bool tiled)
    : width_(map.width), height_(map.height), tiled_(tiled) {
  if (map.layers.empty()) throw std::logic_error("LayersTruth: the map has no layers");
  count_ = map.layers.count;
  depth_ = map.layers.depth;
  normal_ = map.layers.normal;
  color_ = map.layers.color;
}

bool LayersTruth::column_hit(long i, long j, const glm::dvec3& o, const glm::dvec3& d, double t0,
                             double t1, TruthHit& hit) const {
  const long w = width_, h = height_;
  if (!tiled_ && (i < 0 || j < 0 || i >= w || j >= h)) return false;
  const size_t texel = size_t(((j % h) + h) % h) * w + size_t(((i % w) + w) % w);
  const size_t texels = size_t(w) * h;
  float layers[LayerStack::kMaxLayers];
  int n = 0;
  for (int l = 0; l < count_; ++l)
    if (depth_[l * texels + texel] < 1.0f) layers[n++] = depth_[l * texels + texel];
  if (n == 0) return false;
  const double z0 = o.z + d.z * t0, z1 = o.z + d.z * t1;
  // Solid k spans [layers[2k], layers[2k + 1]], the last one open below for an odd count.
  auto solid_end = [&](int k) { return 2 * k + 1 < n ? double(layers[2 * k + 1]) : INFINITY; };
  double t_hit = -1;
  int layer = -1;
  for (int k = 0; 2 * k < n; ++k) {
    const double top = layers[2 * k], bottom = solid_end(k);
    if (z0 > top && z0 < bottom) {  // enters the column inside this solid: its side wall
      t_hit = t0;
      break;
    }
    if (d.z > 0 && top >= z0 && top <= z1) {  // down onto the solid's top
      t_hit = (top - o.z) / d.z;
      layer = 2 * k;
      break;
    }
    if (d.z < 0 && bottom <= z0 && bottom >= z1 && std::isfinite(bottom)) {  // up onto its bottom
      const double t = (bottom - o.z) / d.z;
      if (t_hit < 0 || t < t_hit) {
        t_hit = t;
        layer = 2 * k + 1;
      }
    }
  }
  if (t_hit < 0) return false;
  hit.hit = true;
  hit.t = t_hit;
  hit.point = o + d * t_hit;
  if (layer < 0) {  // a side wall: the layer nearest in depth (Appendix A)
    double best = INFINITY;
    for (int l = 0; l < n; ++l)
      if (std::abs(layers[l] - hit.point.z) < best) {
        best = std::abs(layers[l] - hit.point.z);
        layer = l;
      }
  }
  // Layers are sorted and the used ones come first, so `layer` indexes the stack directly.
  hit.has_normal = true;
  hit.tangent_normal = true;
  hit.normal = glm::dvec3(normal_[layer * texels + texel]);
  hit.has_albedo = true;
  hit.albedo = glm::dvec3(color_[layer * texels + texel]);
  return true;
}

TruthHit LayersTruth::trace(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                            double t_max) const {
  TruthHit hit;
  // Texel (i, j) covers u in [i, i + 1) / width: nearest sampling's cells.
  walk_grid_2d(origin.x * width_, origin.y * height_, direction.x * width_, direction.y * height_,
               t_min, t_max, [&](long i, long j, double t0, double t1) {
                 return column_hit(i, j, origin, direction, t0, t1, hit);
               });
  return hit;
}

TruthHit LayersTruth::intersect(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                                double t_max) const {
  ++primary_rays_;
  return trace(origin, direction, t_min, t_max);
}

bool LayersTruth::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_min,
                           double t_max) const {
  ++shadow_rays_;
  return trace(origin, direction, t_min, t_max).hit;
}

}  // namespace rl
