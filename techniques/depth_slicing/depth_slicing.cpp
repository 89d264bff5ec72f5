// Relief texture mapping by multi-pass depth slicing (chapter 5, Listing 5.2).
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/ray_box.h"
#include "gpu/gpu_heightfield_faces.h"
#include "gpu/scene_uniforms.h"
#include "gpu/texture_space_geometry.h"
#include "relief/heightfield_faces.h"
#include "technique/shader_technique.h"

namespace rl {
namespace {

// Slice depths in the map's texture space, nearest the face first. Over a solid floor the
// slices run from the top (0) to the floor (1) inclusive, so both plateaus are exact and every
// column is drawn at least at the floor (one slice: the floor alone, texture mapping without
// parallax). Over an empty floor or in an object, they are the midpoints of equal slabs.
// The largest distance between neighbouring slices (or the top and the first): over a solid
// floor 1 / (slices - 1), in an object 1 / slices.
double slice_spacing(double slices) {
  return slices > 1 ? 1.0 / (slices - 1) : 1.0;
}

std::vector<double> slice_depths(int slices, bool solid_floor) {
  std::vector<double> d(static_cast<size_t>(slices));
  for (int s = 0; s < slices; ++s)
    d[size_t(s)] =
        solid_floor ? (slices == 1 ? 1.0 : double(s) / (slices - 1)) : (s + 0.5) / slices;
  return d;
}

// The volume the slices cut, as a hexahedron of 8 world corners, corner i at (i & 1, i & 2) on
// the relief's top (i & 4 = 0) or bottom (i & 4 != 0) in u and v.
using Hexahedron = std::array<glm::dvec3, 8>;

// The convex polygon where the plane {x : dot(n, x) = k} cuts the hexahedron, as a triangle
// fan's triangles (empty where it misses).
std::vector<glm::dvec3> plane_cut_triangles(const glm::dvec3& n, double k, const Hexahedron& h) {
  std::vector<glm::dvec3> points;
  for (int bit : {1, 2, 4})
    for (int i = 0; i < 8; ++i) {
      if (i & bit) continue;
      const glm::dvec3 &p0 = h[size_t(i)], &p1 = h[size_t(i | bit)];
      const double s0 = glm::dot(n, p0) - k, s1 = glm::dot(n, p1) - k;
      if ((s0 < 0) == (s1 < 0) || s0 == s1) continue;
      points.push_back(p0 + (p1 - p0) * (s0 / (s0 - s1)));
    }
  std::vector<glm::dvec3> tris;
  if (points.size() < 3) return tris;
  glm::dvec3 centre(0);
  for (const glm::dvec3& p : points) centre += p;
  centre /= double(points.size());
  const glm::dvec3 e1 = glm::normalize(points[0] - centre);
  const glm::dvec3 e2 = glm::cross(glm::normalize(n), e1);
  std::sort(points.begin(), points.end(), [&](const glm::dvec3& p, const glm::dvec3& q) {
    return std::atan2(glm::dot(p - centre, e2), glm::dot(p - centre, e1)) <
           std::atan2(glm::dot(q - centre, e2), glm::dot(q - centre, e1));
  });
  for (size_t i = 1; i + 1 < points.size(); ++i)
    tris.insert(tris.end(), {points[0], points[i], points[i + 1]});
  return tris;
}

// The relief's volume in the world. A box (an object's cube, a box proxy) is its texture-space
// box. A relief drawn on its base is seen only through the base quad: its volume is the quad
// and, below it, the quad scaled away from the eye to the floor, so slices reach what the rays
// entering through the quad reach (and no further). Empty when the eye is not above the base.
std::optional<Hexahedron> relief_volume(const SceneDesc& s, double tile, const Camera& camera) {
  const PlanarBase base = planar_base(s);
  Hexahedron h;
  for (int i = 0; i < 8; ++i)
    h[size_t(i)] = base.world_from_texture({i & 1 ? tile : 0, i & 2 ? tile : 0, i & 4 ? 1 : 0});
  if (s.proxy == Proxy::Box || s.in_cube()) return h;
  const double above = camera.eye.z;  // the base plane is z = 0
  if (above <= 0) return std::nullopt;
  for (int i = 4; i < 8; ++i)
    h[size_t(i)] = camera.eye + (h[size_t(i - 4)] - camera.eye) * ((above + s.depth) / above);
  return h;
}

// The range of dot(forward, x) over the part of the volume the camera sees: its corners in
// the view, and where rays along the viewport's border enter and leave it. View-aligned slices
// spread over this range only: a planar base lengthened for a grazing view reaches far outside
// the viewport, where slices would be wasted.
std::pair<double, double> visible_range(const Camera& camera, const glm::dvec3& forward,
                                        const Hexahedron& volume) {
  glm::dvec3 lo(1e300), hi(-1e300);  // rays are clipped to the volume's bounding box
  for (const glm::dvec3& c : volume) {
    lo = glm::min(lo, c);
    hi = glm::max(hi, c);
  }
  double near = 1e300, far = -1e300;
  auto add = [&](const glm::dvec3& p) {
    near = std::min(near, glm::dot(forward, p));
    far = std::max(far, glm::dot(forward, p));
  };
  const glm::dmat4 view_proj = camera.projection_matrix() * camera.view_matrix();
  for (const glm::dvec3& corner : volume) {
    const glm::dvec4 clip = view_proj * glm::dvec4(corner, 1.0);
    if (clip.w > 0 && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w) add(corner);
  }
  const int steps = 64;
  for (int i = 0; i <= steps; ++i)
    for (int side = 0; side < 4; ++side) {
      const int x = side < 2 ? (camera.width - 1) * i / steps : (side == 2 ? 0 : camera.width - 1);
      const int y =
          side < 2 ? (side == 0 ? 0 : camera.height - 1) : (camera.height - 1) * i / steps;
      glm::dvec3 o, d;
      camera.pixel_ray(x, y, o, d);
      double t_in, t_out;
      if (!clip_ray_to_box(o, d, lo, hi, t_in, t_out)) continue;
      add(o + d * t_in);
      add(o + d * t_out);
    }
  return {near, far};
}

}  // namespace

class DepthSlicing final : public Described<DepthSlicing, Technique> {
 public:
  using Described::Described;
  static TechniqueInfo describe() {
    return {.name = "depth_slicing",
            .title = "Relief texture mapping by multi-pass depth slicing",
            .citation =
                "Chapter 5, 'RTM - Multi pass for planar objects', Listing 5.2, "
                "Figures 5.6-5.8",
            .effects = {Effect::DepthCorrect},
            .params = {{.name = "slices",
                        .kind = ParamKind::Int,
                        .default_value = 32,
                        .min_value = 1,
                        .max_value = 256,
                        .doc = "slice planes (passes per relief texture): the level of detail "
                               "of Figure 5.7",
                        .define = "RL_SLICES"},
                       {.name = "view_aligned",
                        .kind = ParamKind::Bool,
                        .default_value = 0,
                        .min_value = 0,
                        .max_value = 1,
                        .doc = "slices normal to the view direction across the volume (one set "
                               "for all faces) instead of parallel to each relief texture "
                               "(Figure 5.8)",
                        .define = "RL_VIEW_ALIGNED",
                        .define_when_set = true}},
            .draws = {.reads = {Representation::Heightfield, Representation::HeightfieldObject},
                      .bases = {BaseShape::Planar},
                      .proxies = {Proxy::Base, Proxy::Box},
                      .projections = {Projection::Plain}},
            .contract = {
                .answer = Answer::Converging,
                .max_fetches =
                    [](const RayQuery& q) {
                      const double slices = q.param("slices");
                      return q.faces > 1 ? slices * q.faces * (q.faces + 2) : 2 * slices;
                    },
                .max_fetches_formula = "2 x slices: a depth and a colour per slice fragment; on "
                                       "an object, slices x faces fragments, each testing every "
                                       "face and shading from 2 more",
                .knobs = {{"slices"}},
                .finest = {{"slices", 256}},
                .t_error = [](const RayQuery& q) { return slice_spacing(q.param("slices")); },
                .accuracy = "the first slice behind the surface: within one slice spacing (1 / "
                            "(slices - 1) of depth over a solid floor, planes 0 to 1 inclusive) "
                            "along the ray, on surfaces with no feature thinner than a slice",
                .t_resolution = [](const RayQuery& q) { return slice_spacing(q.param("slices")); }},
            .columns = {{"slice_passes", "passes", "slice passes drawn for the frame"},
                        {"fragments_per_pixel", "fragments",
                         "slice fragments shaded per covered pixel, summed over the passes"},
                        {"fragments_max", "fragments", "the most slice fragments of one pixel"}}};
  }
  ~DepthSlicing() override {
    if (fragment_count_) glDeleteTextures(1, &fragment_count_);
    if (fetch_count_) glDeleteTextures(1, &fetch_count_);
    if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
  }

  void render(const FrameInput& frame, RenderTarget::Kind target) override {
    const SceneDesc& s = frame.scene;
    const bool counting = target == RenderTarget::Kind::GBuffer;
    const int slices = slice_count_;
    ProgramDesc d = program(s, frame.map);
    d.vertex_file = "harness/glsl/texture_space.vert";
    if (counting) {
      d.defines["RL_GBUFFER"] = "1";
      d.defines["RL_COUNT_FRAGMENTS"] = "1";
    }
    const GLuint p = ShaderLibrary::shared().program(d);
    glUseProgram(p);
    set_scene_uniforms(p, s, frame.camera);
    set_texture_space_uniforms(p, s, frame.camera);
    if (frame.map.faces) set_heightfield_faces_uniforms(p, *frame.map.faces);
    frame.relief.bind();

    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    if (counting) prepare_counters(viewport[2], viewport[3]);

    const std::vector<std::vector<glm::vec3>> passes = slice_passes(frame, slices);
    std::vector<glm::vec3> all;
    std::vector<std::pair<GLint, GLsizei>> ranges;
    for (const auto& pass : passes) {
      ranges.push_back({GLint(all.size()), GLsizei(pass.size())});
      all.insert(all.end(), pass.begin(), pass.end());
    }
    slices_.set(all);
    // Slices are seen from either side; the depth test keeps the nearest kept fragment.
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    for (const auto& [first, count] : ranges) slices_.draw(GL_TRIANGLES, first, count);
    passes_ = int(ranges.size());
    if (counting) resolve(viewport[2], viewport[3]);
  }

  std::vector<std::pair<std::string, double>> frame_columns() const override {
    return {{"slice_passes", double(passes_)},
            {"fragments_per_pixel", fragments_per_pixel_},
            {"fragments_max", double(fragments_max_)}};
  }

  // The slicing rule along probe rays: tangent-space rays (direction.z = 1) on a plain map, or
  // cube-space rays from inside the cube on heightfield faces; the nearest kept slice point.
  std::vector<ProbeHit> probe(const ReliefMap& map, const GpuRelief& relief,
                              const std::vector<ProbeRay>& rays, glm::dvec2) override {
    if (rays.empty()) return {};
    const int slices = slice_count_;
    // A probe has no scene: a plain map has a solid floor, faces make an object.
    SceneDesc probe_scene;
    probe_scene.relief.faces = map.faces ? map.faces->count() : 0;
    ProgramDesc d = program(probe_scene, map);
    d.vertex_file = "harness/glsl/fullscreen.vert";
    d.defines["RL_PROBE"] = "1";
    const GLuint p = ShaderLibrary::shared().program(d);
    const std::vector<double> depths = slice_depths(slices, !map.faces);
    std::vector<float> f(depths.begin(), depths.end());
    glProgramUniform1fv(p, glGetUniformLocation(p, "rl_slice_depth"), GLsizei(f.size()), f.data());
    if (map.faces) set_heightfield_faces_uniforms(p, *map.faces);
    const GBuffer out = run_probe_pass(p, rays, [&] { relief.bind(); });
    return decode_probe_hits(out, rays.size());
  }

 private:
  ProgramDesc program(const SceneDesc& s, const ReliefMap& map) const {
    ProgramDesc d;
    d.owner = info().name;
    d.fragment_files = {"techniques/depth_slicing/depth_slicing.glsl"};
    d.defines = declared_defines();
    // A slice exactly at a stored 8-bit depth counts as behind it whatever the rounding; a float
    // map needs no slack, which would keep slices above the surface.
    d.defines["RL_SLICE_SLACK"] = map.quantized ? "(0.5 / 255.0)" : "0.0";
    if (s.heightfield_object()) d.defines["RL_FACES"] = "1";
    if (s.empty_floor && !s.heightfield_object()) d.defines["RL_EMPTY_FLOOR"] = "1";
    return d;
  }

  // One triangle list per pass, in texture space: per relief texture (face) and slice, the slice
  // plane across the volume; or view-aligned, per slice one plane normal to the camera's forward
  // axis, clipped to the volume.
  std::vector<std::vector<glm::vec3>> slice_passes(const FrameInput& frame, int slices) const {
    const SceneDesc& s = frame.scene;
    const HeightfieldFaces* faces = frame.map.faces.get();
    const double tile = faces ? 1.0 : s.tile;
    std::vector<std::vector<glm::vec3>> passes;
    const std::optional<Hexahedron> volume = relief_volume(s, tile, frame.camera);
    if (!volume) return passes;  // the base is seen from below or edge-on: nothing to slice
    const PlanarBase base = planar_base(s);
    if (view_aligned_) {
      const glm::dvec3 forward = glm::normalize(frame.camera.target - frame.camera.eye);
      const auto [near, far] = visible_range(frame.camera, forward, *volume);
      for (int i = 0; i < slices; ++i) {
        const double k = near + (far - near) * (i + 0.5) / slices;
        std::vector<glm::vec3> pass;
        for (const glm::dvec3& w : plane_cut_triangles(forward, k, *volume))
          pass.push_back(glm::vec3(base.texture_from_world(w)));
        passes.push_back(pass);
      }
      return passes;
    }
    const std::vector<double> depths = slice_depths(slices, !s.empty_floor && !faces);
    if (!faces) {
      // Planes of constant depth across the volume: its side edges at that depth.
      for (double depth : depths) {
        glm::vec3 c[4];
        for (int i = 0; i < 4; ++i)
          c[i] = glm::vec3(base.texture_from_world(
              glm::mix((*volume)[size_t(i)], (*volume)[size_t(i + 4)], depth)));
        passes.push_back({c[0], c[1], c[3], c[0], c[3], c[2]});
      }
      return passes;
    }
    for (int k = 0; k < faces->count(); ++k) {
      const glm::dmat3 cube_from_face = glm::transpose(face_from_cube(faces->faces[size_t(k)]));
      for (double depth : depths) {
        // The slice in the face's affine space (a plane of constant texture depth there too).
        const double z = faces->projection.affine_from_texture({0.5, 0.5, depth}).z;
        const glm::dvec3 q[4] = {{0, 0, z}, {1, 0, z}, {1, 1, z}, {0, 1, z}};
        glm::vec3 c[4];
        for (int i = 0; i < 4; ++i) c[i] = glm::vec3(cube_from_face * (q[i] - 0.5) + 0.5);
        passes.push_back({c[0], c[1], c[2], c[0], c[2], c[3]});
      }
    }
    return passes;
  }

  void prepare_counters(int width, int height) {
    if (width != count_width_ || height != count_height_) {
      if (fragment_count_) glDeleteTextures(1, &fragment_count_);
      if (fetch_count_) glDeleteTextures(1, &fetch_count_);
      for (GLuint* t : {&fragment_count_, &fetch_count_}) {
        glCreateTextures(GL_TEXTURE_2D, 1, t);
        glTextureStorage2D(*t, 1, GL_R32UI, width, height);
      }
      count_width_ = width;
      count_height_ = height;
    }
    const GLuint zero = 0;
    glClearTexImage(fragment_count_, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glClearTexImage(fetch_count_, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindImageTexture(0, fragment_count_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindImageTexture(1, fetch_count_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  }

  // The per-pixel sums into the G-buffer's fetch channel, and the fragment statistics.
  void resolve(int width, int height) {
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    ProgramDesc d;
    d.owner = info().name;
    d.vertex_file = "harness/glsl/fullscreen.vert";
    d.fragment_files = {"techniques/depth_slicing/depth_slicing_resolve.glsl"};
    const GLuint p = ShaderLibrary::shared().program(d);
    glUseProgram(p);
    for (GLuint i = 0; i < 5; ++i) glColorMaski(i, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glColorMaski(3, GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    if (!empty_vao_) glCreateVertexArrays(1, &empty_vao_);
    glBindVertexArray(empty_vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    for (GLuint i = 0; i < 5; ++i) glColorMaski(i, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glEnable(GL_DEPTH_TEST);
    std::vector<GLuint> counts(size_t(width) * height);
    glGetTextureImage(fragment_count_, 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                      GLsizei(counts.size() * sizeof(GLuint)), counts.data());
    double total = 0;
    long touched = 0;
    fragments_max_ = 0;
    for (GLuint c : counts) {
      if (!c) continue;
      total += c;
      ++touched;
      fragments_max_ = std::max(fragments_max_, long(c));
    }
    fragments_per_pixel_ = touched ? total / double(touched) : 0.0;
  }

  const int slice_count_ = param<int>("slices");
  const bool view_aligned_ = param<bool>("view_aligned");
  PositionBuffer slices_;
  GLuint fragment_count_ = 0, fetch_count_ = 0, empty_vao_ = 0;
  int count_width_ = 0, count_height_ = 0;
  int passes_ = 0;
  double fragments_per_pixel_ = 0;
  long fragments_max_ = 0;
};

RL_REGISTER_TECHNIQUE(DepthSlicing);

}  // namespace rl
