#pragma once
// The G-buffer both a technique and the truth fill, so every metric compares like with like.
// Pixel (x, y) is at index y * width + x with y = 0 the bottom row (GL's convention).
#include <vector>

#include <glm/glm.hpp>

namespace rl {

struct GBuffer {
  int width = 0, height = 0;
  std::vector<glm::vec4> color;     // shaded rgb; a = coverage (1 = relief hit)
  std::vector<glm::vec4> position;  // world-space hit; w = coverage
  std::vector<glm::vec4> normal;    // world-space shading normal; w = 1 if in shadow
  std::vector<glm::vec4> hit;       // hit u, v, layer, texture fetches of this pixel
  // x: ambient visibility the pixel was shaded with (1 without ambient_occlusion); y: its
  // standard error (the truth's hemisphere sampling; 0 for a technique); z: the unoccluded
  // ambient term's mean over rgb (ambient * albedo), so AO's share of colour error is known;
  // w: the truth's bound on this pixel's hit, a world distance along the camera ray
  // (truth/truth_render.h truth_hit_bound; 0 in a technique's G-buffer).
  std::vector<glm::vec4> aux;

  void resize(int w, int h) {
    width = w;
    height = h;
    const size_t n = static_cast<size_t>(w) * h;
    color.assign(n, glm::vec4(0));
    position.assign(n, glm::vec4(0));
    normal.assign(n, glm::vec4(0));
    hit.assign(n, glm::vec4(0));
    aux.assign(n, glm::vec4(0));
  }
  size_t size() const { return color.size(); }
  bool covered(size_t i) const { return color[i].a > 0.5f; }
  bool shadowed(size_t i) const { return normal[i].w > 0.5f; }
};

}  // namespace rl
