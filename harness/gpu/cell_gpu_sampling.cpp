#include "gpu/cell_gpu_sampling.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <epoxy/gl.h>

#include "core/elapsed.h"
#include "core/error.h"
#include "gl/context.h"
#include "gl/shader_library.h"

namespace rl {
namespace {

// Per grey cell (in cells() order), the mesh triangles intersecting it, as the paper draws them:
// the exact test the classification made the cell grey by (triangle_overlaps_box, with its
// hair of padding), over the cells the triangle's bounding box meets.
std::vector<std::vector<uint32_t>> triangles_per_cell(const CellComplex& cc) {
  const int n = cc.grid();
  const TriangleMesh& mesh = cc.mesh();
  std::vector<std::vector<uint32_t>> out(cc.cells().size());
  const double slack = 1e-6, pad = 1e-9;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    glm::dvec3 corner[3];
    for (int k = 0; k < 3; ++k) corner[k] = glm::dvec3(mesh.positions[mesh.triangles[t][k]]);
    const glm::dvec3 lo = glm::min(corner[0], glm::min(corner[1], corner[2])) * double(n);
    const glm::dvec3 hi = glm::max(corner[0], glm::max(corner[1], corner[2])) * double(n);
    const glm::ivec3 from = glm::clamp(glm::ivec3(glm::floor(lo - slack)), 0, n - 1);
    const glm::ivec3 to = glm::clamp(glm::ivec3(glm::floor(hi + slack)), 0, n - 1);
    for (int k = from.z; k <= to.z; ++k)
      for (int j = from.y; j <= to.y; ++j)
        for (int i = from.x; i <= to.x; ++i) {
          if (cc.cell(i, j, k).state != CellState::Grey) continue;
          const glm::dvec3 box_lo = glm::dvec3(i, j, k) / double(n) - pad;
          const glm::dvec3 box_hi = glm::dvec3(i + 1, j + 1, k + 1) / double(n) + pad;
          if (triangle_overlaps_box(corner[0], corner[1], corner[2], box_lo, box_hi))
            out[cc.index(i, j, k)].push_back(uint32_t(t));
        }
  }
  return out;
}

// The mesh's vertices and, cell after cell, the indices of its triangles; where each cell's
// start (in indices) and count.
struct CellDrawBuffers {
  GLuint vao = 0, vertices = 0, indices = 0;
  std::vector<size_t> first, count;

  explicit CellDrawBuffers(const CellComplex& cc) {
    const TriangleMesh& mesh = cc.mesh();
    std::vector<uint32_t> index;
    for (const std::vector<uint32_t>& tris : triangles_per_cell(cc)) {
      first.push_back(index.size());
      for (uint32_t t : tris)
        for (int k = 0; k < 3; ++k) index.push_back(mesh.triangles[t][k]);
      count.push_back(index.size() - first.back());
    }
    glCreateVertexArrays(1, &vao);
    glCreateBuffers(1, &vertices);
    glCreateBuffers(1, &indices);
    glNamedBufferStorage(vertices, GLsizeiptr(mesh.positions.size() * sizeof(glm::vec3)),
                         mesh.positions.data(), 0);
    glNamedBufferStorage(indices, GLsizeiptr(std::max<size_t>(1, index.size()) * 4),
                         index.empty() ? nullptr : index.data(), 0);
    glVertexArrayVertexBuffer(vao, 0, vertices, 0, sizeof(glm::vec3));
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayElementBuffer(vao, indices);
  }
  ~CellDrawBuffers() {
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(1, &vertices);
    glDeleteBuffers(1, &indices);
  }
  CellDrawBuffers(const CellDrawBuffers&) = delete;
  CellDrawBuffers& operator=(const CellDrawBuffers&) = delete;
};

// One face's maps: float colours (the distance; the normal) and a depth-stencil buffer (the
// distance again, for the test; the fragments counted).
struct FaceTarget {
  GLuint fbo = 0, color = 0, normal = 0, depth = 0;

  explicit FaceTarget(int res) {
    glCreateTextures(GL_TEXTURE_2D, 1, &color);
    glTextureStorage2D(color, 1, GL_R32F, res, res);
    glCreateTextures(GL_TEXTURE_2D, 1, &normal);
    glTextureStorage2D(normal, 1, GL_RGBA32F, res, res);  // RGB32F need not be renderable
    glCreateRenderbuffers(1, &depth);
    glNamedRenderbufferStorage(depth, GL_DEPTH32F_STENCIL8, res, res);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color, 0);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, normal, 0);
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo, 2, buffers);
    glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth);
    if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError("cell complex GPU sampling: the face's render target is incomplete");
  }
  ~FaceTarget() {
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &color);
    glDeleteTextures(1, &normal);
    glDeleteRenderbuffers(1, &depth);
  }
  FaceTarget(const FaceTarget&) = delete;
  FaceTarget& operator=(const FaceTarget&) = delete;
};

void set_face_uniforms(GLuint program, const CellComplex& cc, const CellComplex::DomainFace& df) {
  const int n = cc.grid();
  const CellProjection& p = cc.cells()[df.cell].config.projection;
  const glm::vec3 origin(float(df.cell % n), float((df.cell / n) % n), float(df.cell / (n * n)));
  glProgramUniform3fv(program, glGetUniformLocation(program, "rl_cell_origin"), 1, &origin.x);
  glProgramUniform1i(program, glGetUniformLocation(program, "rl_face"), df.face);
  glProgramUniform1i(program, glGetUniformLocation(program, "rl_projection"), int(p.type));
  const glm::vec3 point(p.point);
  glProgramUniform3fv(program, glGetUniformLocation(program, "rl_projection_point"), 1, &point.x);
  glProgramUniform1i(program, glGetUniformLocation(program, "rl_projection_axis"), p.axis);
}

// The geometry shader's first-level pieces per edge where it cuts (cell_sampling_geom.glsl).
constexpr int kSplits = 5;

GLuint sampling_program(int splits) {
  return ShaderLibrary::shared().program({"cell_complex GPU sampling",
                                          "harness/glsl/cell_sampling.vert",
                                          {"harness/glsl/cell_sampling_frag.glsl"},
                                          {{"RL_CELL_SPLITS", std::to_string(splits)}},
                                          "harness/glsl/cell_sampling_geom.glsl"});
}

// Mean, 99th percentile and largest of `v` (reordered); zeros when it is empty.
struct Spread {
  double mean = 0, p99 = 0, max = 0;
};

Spread spread_of(std::vector<double>& v) {
  Spread s;
  if (v.empty()) return s;
  for (double x : v) s.mean += x;
  s.mean /= double(v.size());
  s.max = *std::max_element(v.begin(), v.end());
  const size_t p99 = std::min(v.size() - 1, size_t(0.99 * double(v.size())));
  std::nth_element(v.begin(), v.begin() + long(p99), v.end());
  s.p99 = v[p99];
  return s;
}

// One texel's fragments, as the GPU's stencil and the CPU's crossings count them.
void count_fragments(int gpu, int cpu, CellSamplingAgreement::PerType& type) {
  type.gpu_fragments += gpu;
  type.cpu_fragments += cpu;
  type.gpu_occluded += std::max(0, gpu - 1);
  type.cpu_occluded += std::max(0, cpu - 1);
  type.fragment_counts_differ += gpu != cpu;
}

// In double, and by atan2: acos of a float dot product near 1 cannot resolve below ~0.02 deg.
double degrees_between(glm::dvec3 a, glm::dvec3 b) {
  return glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

}  // namespace

CellGpuSampling sample_cell_maps_on_gpu(const CellComplex& cc,
                                        const CellGpuSamplingOptions& options) {
  GlContext::shared();
  // Cells whose triangles are cut (axial ones, with a threshold) draw through the geometry
  // shader's instanced form; the others through one invocation per triangle.
  const GLuint whole = sampling_program(1), cut = sampling_program(kSplits);
  const int res = cc.resolution();
  for (GLuint program : {whole, cut}) {
    glProgramUniform1f(program, glGetUniformLocation(program, "rl_grid"), float(cc.grid()));
    glProgramUniform1f(program, glGetUniformLocation(program, "rl_res"), float(res));
    glProgramUniform1f(program, glGetUniformLocation(program, "rl_subdivide_texels"),
                       float(options.subdivide_texels));
  }
  CellDrawBuffers draws(cc);
  FaceTarget target(res);
  const size_t texels = size_t(res) * res;
  CellGpuSampling out;
  out.distance.assign(cc.domain_faces().size() * texels, 1.0f);
  out.normal.assign(out.distance.size(), glm::vec3(0.0f));
  out.fragments.assign(out.distance.size(), 0);
  std::vector<glm::vec4> face_normal(texels);

  glFinish();
  const auto t0 = std::chrono::steady_clock::now();
  glBindFramebuffer(GL_FRAMEBUFFER, target.fbo);
  glViewport(0, 0, res, res);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  // Every fragment the shader keeps adds one to its texel's stencil, occluded or not.
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, 0, 0xff);
  glStencilOp(GL_KEEP, GL_INCR, GL_INCR);
  glStencilMask(0xff);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glBindVertexArray(draws.vao);
  const GLfloat far_distance = 1.0f, far_depth = 1.0f, no_normal[4] = {0, 0, 0, 0};
  for (size_t f = 0; f < cc.domain_faces().size(); ++f) {
    const CellComplex::DomainFace& df = cc.domain_faces()[f];
    const bool axial = cc.cells()[df.cell].config.projection.type == CellProjection::Type::Axial;
    const GLuint program = axial && options.subdivide_texels > 0 ? cut : whole;
    glUseProgram(program);
    set_face_uniforms(program, cc, df);
    glClearNamedFramebufferfv(target.fbo, GL_COLOR, 0, &far_distance);
    glClearNamedFramebufferfv(target.fbo, GL_COLOR, 1, no_normal);
    glClearNamedFramebufferfi(target.fbo, GL_DEPTH_STENCIL, 0, far_depth, 0);
    const size_t count = draws.count[df.cell];
    if (count)
      glDrawElements(GL_TRIANGLES, GLsizei(count), GL_UNSIGNED_INT,
                     reinterpret_cast<const void*>(draws.first[df.cell] * sizeof(uint32_t)));
    glNamedFramebufferReadBuffer(target.fbo, GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, res, res, GL_RED, GL_FLOAT, out.distance.data() + f * texels);
    glNamedFramebufferReadBuffer(target.fbo, GL_COLOR_ATTACHMENT1);
    glReadPixels(0, 0, res, res, GL_RGBA, GL_FLOAT, face_normal.data());
    for (size_t t = 0; t < texels; ++t) out.normal[f * texels + t] = glm::vec3(face_normal[t]);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);  // rows of `res` bytes
    glReadPixels(0, 0, res, res, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE,
                 out.fragments.data() + f * texels);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    ++out.face_draws;
    out.triangles += long(count / 3);
  }
  glFinish();
  out.ms = ms_since(t0);
  // GL's defaults back, for whatever draws next in this context.
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glUseProgram(0);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  return out;
}

CellComplex with_gpu_sampled_maps(const CellComplex& cc) {
  const CellGpuSampling gpu = sample_cell_maps_on_gpu(cc, {.subdivide_texels = 1});
  return cc.with_sampled_maps(gpu.distance, gpu.normal);
}

CellSamplingAgreement compare_cell_sampling(const CellComplex& cc, const CellGpuSampling& gpu) {
  const int res = cc.resolution();
  const size_t texels = size_t(res) * res;
  if (gpu.distance.size() != cc.domain_faces().size() * texels ||
      gpu.normal.size() != gpu.distance.size() || gpu.fragments.size() != gpu.distance.size())
    throw std::invalid_argument("compare_cell_sampling: the GPU maps are not the complex's size");
  CellSamplingAgreement out;
  std::array<std::vector<double>, 4> errors, angles;
  for (size_t f = 0; f < cc.domain_faces().size(); ++f) {
    const CellComplex::DomainFace& df = cc.domain_faces()[f];
    const CellProjection& p = cc.cells()[df.cell].config.projection;
    CellSamplingAgreement::PerType& type = out.types[int(p.type)];
    for (size_t t = 0; t < texels; ++t) {
      const size_t at = f * texels + t;
      const bool cpu_hit = cc.crossings()[at] > 0, gpu_hit = gpu.distance[at] < 1.0f;
      ++type.texels;
      type.cpu_hits += cpu_hit;
      count_fragments(gpu.fragments[at], cc.crossings()[at], type);
      const double cpu_d = cc.distance()[at] / cc.distance_scale();
      if (cpu_hit != gpu_hit) {
        const double d = gpu_hit ? double(gpu.distance[at]) : cpu_d;
        ++type.one_sided;
        type.one_sided_at_ends += d < 1e-4 || d > 0.99;
      }
      if (!cpu_hit || !gpu_hit) continue;
      ++type.both_hit;
      const glm::dvec2 st((double(t % res) + 0.5) / res, (double(t / res) + 0.5) / res);
      const double length = face_line(p, df.face, st).length;
      const double err = std::abs(double(gpu.distance[at]) - cpu_d) * length * res;
      type.within_half += err <= 0.5;
      type.over_one += err > 1.0;
      errors[int(p.type)].push_back(err);
      const double angle = degrees_between(gpu.normal[at], cc.normal()[at]);
      type.normal_over_1deg += angle > 1.0;
      angles[int(p.type)].push_back(angle);
    }
  }
  for (int k = 0; k < 4; ++k) {
    CellSamplingAgreement::PerType& type = out.types[k];
    const Spread e = spread_of(errors[k]), a = spread_of(angles[k]);
    type.err_texels_mean = e.mean;
    type.err_texels_p99 = e.p99;
    type.err_texels_max = e.max;
    type.normal_err_deg_mean = a.mean;
    type.normal_err_deg_p99 = a.p99;
    type.normal_err_deg_max = a.max;
  }
  return out;
}

}  // namespace rl
