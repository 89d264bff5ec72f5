#include "output/gbuffer_export.h"

#include <filesystem>
#include <stdexcept>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "relief/image_io.h"

namespace rl {

namespace {

ImageAttribute matrix(const char* name, const glm::dmat4& m) {
  const glm::mat4 f(m);
  const float* p = glm::value_ptr(f);
  return {name, ImageAttribute::Kind::Matrix44, std::vector<float>(p, p + 16), {}, {}};
}

ImageAttribute number(const char* name, double v) {
  return {name, ImageAttribute::Kind::Float, {float(v)}, {}, {}};
}

ImageAttribute text(const char* name, const std::string& v) {
  return {name, ImageAttribute::Kind::String, {}, {}, v};
}

}  // namespace

void write_gbuffer_exr(const std::string& path, const GBuffer& g, const SceneDesc& scene,
                       const Camera& camera, const GBufferLabels& labels) {
  const bool planar = !scene.base.curved();
  std::vector<std::string> names = {"R",   "G",     "B",       "A",     "P.X",  "P.Y",
                                    "P.Z", "N.X",   "N.Y",     "N.Z",   "uv.U", "uv.V",
                                    "Z",   "layer", "fetches", "shadow"};
  const int relief_depth_channel = int(names.size());
  if (planar) names.push_back("relief_depth");
  const int bound_channel = int(names.size());
  names.push_back("truth_bound");
  // The ambient visibility shaded with, and its standard error (the truth's sampling).
  const bool ambient_occlusion = scene.effects.has(Effect::AmbientOcclusion);
  const int ao_channel = int(names.size());
  if (ambient_occlusion) names.insert(names.end(), {"ao", "ao_stderr"});
  const int channels = int(names.size());
  const glm::dmat4 view = camera.view_matrix(), projection = camera.projection_matrix();
  const PlanarBase base = planar_base(scene);

  std::vector<float> px(size_t(g.width) * g.height * channels, 0.0f);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const size_t i = size_t(y) * g.width + x;
      if (!g.covered(i)) continue;
      // GL's row 0 is the bottom; the file's first row is the top.
      float* p = &px[(size_t(g.height - 1 - y) * g.width + x) * channels];
      const glm::vec4 c = g.color[i], pos = g.position[i], n = g.normal[i], hit = g.hit[i];
      const glm::dvec3 world(pos);
      const double z = -(view * glm::dvec4(world, 1.0)).z;
      const float values[] = {
          c.r, c.g, c.b,   1.0f,  pos.x,    pos.y, pos.z, n.x,
          n.y, n.z, hit.x, hit.y, float(z), hit.z, hit.w, n.w > 0.5f ? 1.0f : 0.0f};
      std::copy(std::begin(values), std::end(values), p);
      if (planar) {
        // Texture depth through the base (and a baked mesh's reverse projection, if any).
        const glm::dvec3 t = scene.projection.texture_from_affine(base.texture_from_world(world));
        p[relief_depth_channel] = float(t.z);
      }
      p[bound_channel] = g.aux[i].w;
      if (ambient_occlusion) {
        p[ao_channel] = g.aux[i].x;
        p[ao_channel + 1] = g.aux[i].y;
      }
    }

  ImageWriteSpec spec;
  spec.width = g.width;
  spec.height = g.height;
  spec.channels = channels;
  spec.float_pixels = true;
  spec.channel_names = names;
  spec.alpha_channel = 3;
  spec.z_channel = 12;
  auto& a = spec.attributes;
  a.push_back(text("compression", "zip"));
  a.push_back(matrix("worldtocamera", view));
  a.push_back(matrix("worldtoscreen", projection * view));
  a.push_back(matrix("relieflab:view", view));
  a.push_back(matrix("relieflab:projection", projection));
  a.push_back({"relieflab:viewport",
               ImageAttribute::Kind::Box2i,
               {},
               {0, 0, g.width - 1, g.height - 1},
               {}});
  a.push_back({"relieflab:eye",
               ImageAttribute::Kind::Vector3,
               {float(camera.eye.x), float(camera.eye.y), float(camera.eye.z)},
               {},
               {}});
  a.push_back(number("relieflab:fov_y_deg", camera.fov_y_deg));
  a.push_back(number("relieflab:near", camera.near_plane));
  a.push_back(number("relieflab:far", camera.far_plane));
  a.push_back(text("relieflab:scene", labels.scene));
  if (!labels.technique.empty()) a.push_back(text("relieflab:technique", labels.technique));
  if (!labels.params.empty()) a.push_back(text("relieflab:params", labels.params));
  a.push_back(text("relieflab:key", labels.key));

  write_image_file(path, spec, px.data());
}

}  // namespace rl
