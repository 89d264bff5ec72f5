#include "gpu/gpu_ao_map.h"

#include <algorithm>
#include <chrono>

#include "core/elapsed.h"
#include "gl/context.h"
#include "gl/render_target.h"
#include "gl/shader_library.h"

namespace rl {

AoMapMethod ao_map_method(AmbientOcclusionDesc::MapMethod method) {
  switch (method) {
    case AmbientOcclusionDesc::MapMethod::March:
      return {"march", compute_ao_map_march};
    case AmbientOcclusionDesc::MapMethod::FragmentShader:
      return {"fragment_shader", compute_ao_map_gpu};
    case AmbientOcclusionDesc::MapMethod::LineSweep:
      break;
  }
  return {};
}

AoMap compute_ao_map_gpu(const ReliefMap& map, const AoMapOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  GlContext::shared();
  std::vector<float> heights(map.relief.size());
  for (size_t i = 0; i < heights.size(); ++i)
    heights[i] = float((1.0 - double(map.relief[i].a)) * o.height_texels);
  GLuint tex = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &tex);
  glTextureStorage2D(tex, 1, GL_R32F, map.width, map.height);
  glTextureSubImage2D(tex, 0, 0, 0, map.width, map.height, GL_RED, GL_FLOAT, heights.data());
  glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);

  ProgramDesc desc;
  desc.owner = "ao_map";
  desc.vertex_file = "harness/glsl/fullscreen.vert";
  desc.fragment_files = {"harness/glsl/ao_map.frag"};
  const GLuint program = ShaderLibrary::shared().program(desc);
  RenderTarget target(map.width, map.height, RenderTarget::Kind::GBuffer);
  target.bind_and_clear();
  glUseProgram(program);
  glProgramUniform1i(program, glGetUniformLocation(program, "rl_directions"),
                     std::max(3, o.directions));
  glProgramUniform1i(program, glGetUniformLocation(program, "rl_max_steps"),
                     2 * std::max(map.width, map.height));
  glProgramUniform1f(program, glGetUniformLocation(program, "rl_highest"),
                     *std::max_element(heights.begin(), heights.end()));
  glBindTextureUnit(0, tex);
  glDisable(GL_DEPTH_TEST);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  glBindVertexArray(vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  GBuffer out;
  target.read_back(out);  // waits for the draw
  glDeleteVertexArrays(1, &vao);
  glDeleteTextures(1, &tex);

  AoMap ao;
  ao.width = map.width;
  ao.height = map.height;
  ao.visibility.resize(out.color.size());
  for (size_t i = 0; i < out.color.size(); ++i) ao.visibility[i] = out.color[i].r;
  if (o.filter) filter_occluded_texels(map, ao.visibility);
  ao.compute_ms = ms_since(start);
  return ao;
}

}  // namespace rl
