#include "gl/op_counting.h"

#include <glslang/Include/glslang_c_interface.h>
#include <glslang/Public/resource_limits_c.h>
#include <spirv_cross/spirv_cross_c.h>

#include <memory>
#include <mutex>
#include <stdexcept>

#include "core/hash.h"
#include "core/op_kinds.h"
#include "core/precompute_cache.h"
#include "gl/spirv_op_counts.h"

namespace rl {
namespace {

void initialise_glslang() {
  static std::once_flag once;
  std::call_once(once, [] { glslang_initialize_process(); });
}

glslang_input_t fragment_input(const std::string& source) {
  glslang_input_t in{};
  in.language = GLSLANG_SOURCE_GLSL;
  in.stage = GLSLANG_STAGE_FRAGMENT;
  in.client = GLSLANG_CLIENT_OPENGL;
  in.client_version = GLSLANG_TARGET_OPENGL_450;
  in.target_language = GLSLANG_TARGET_SPV;
  in.target_language_version = GLSLANG_TARGET_SPV_1_0;
  in.code = source.c_str();
  in.default_version = 450;
  in.default_profile = GLSLANG_CORE_PROFILE;
  in.messages = GLSLANG_MSG_DEFAULT_BIT;
  in.resource = glslang_default_resource();
  return in;
}

struct ShaderDeleter {
  void operator()(glslang_shader_t* s) const { glslang_shader_delete(s); }
};
struct ProgramDeleter {
  void operator()(glslang_program_t* p) const { glslang_program_delete(p); }
};
struct ContextDeleter {
  void operator()(spvc_context c) const { spvc_context_destroy(c); }
};

std::string glslang_failure(const char* stage, const char* log) {
  return std::string("op counting: glslang could not ") + stage + " the shader:\n" +
         (log ? log : "");
}

std::string spirv_cross_failure(spvc_context context, const char* what) {
  return std::string("op counting: SPIRV-Cross could not ") + what + ": " +
         spvc_context_get_last_error_string(context);
}

// GLSL 4.50 core from `spirv`, as SPIRV-Cross writes it back.
std::string glsl_of(const std::vector<uint32_t>& spirv) {
  spvc_context raw = nullptr;
  if (spvc_context_create(&raw) != SPVC_SUCCESS)
    throw std::runtime_error("op counting: SPIRV-Cross could not start");
  std::unique_ptr<spvc_context_s, ContextDeleter> context(raw);
  spvc_parsed_ir ir = nullptr;
  spvc_compiler compiler = nullptr;
  spvc_compiler_options options = nullptr;
  if (spvc_context_parse_spirv(raw, spirv.data(), spirv.size(), &ir) != SPVC_SUCCESS)
    throw std::runtime_error(spirv_cross_failure(raw, "read the instrumented SPIR-V"));
  if (spvc_context_create_compiler(raw, SPVC_BACKEND_GLSL, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP,
                                   &compiler) != SPVC_SUCCESS ||
      spvc_compiler_create_compiler_options(compiler, &options) != SPVC_SUCCESS)
    throw std::runtime_error(spirv_cross_failure(raw, "set up its GLSL writer"));
  spvc_compiler_options_set_uint(options, SPVC_COMPILER_OPTION_GLSL_VERSION, 450);
  spvc_compiler_options_set_bool(options, SPVC_COMPILER_OPTION_GLSL_ES, SPVC_FALSE);
  // Globals declared with a value: a compiler that reads the functions before main would
  // otherwise warn that each is used uninitialised (main still assigns them first).
  spvc_compiler_options_set_bool(options, SPVC_COMPILER_OPTION_FORCE_ZERO_INITIALIZED_VARIABLES,
                                 SPVC_TRUE);
  spvc_compiler_install_compiler_options(compiler, options);
  const char* text = nullptr;
  if (spvc_compiler_compile(compiler, &text) != SPVC_SUCCESS)
    throw std::runtime_error(spirv_cross_failure(raw, "write GLSL"));
  return text;
}

// `source` whose main() runs only in the lockstep groups counted: the pass's own main renamed,
// and a new one that first lets the gate discard the other groups. The gate is named
// rl_uncounted_*, so its work is not counted (gl/spirv_op_counts.h); main's own block only
// calls. Groups are quad-aligned, so no derivative reads a discarded neighbour.
std::string with_group_gate(const std::string& source, int group_stride) {
  if (group_stride <= 1) return source;
  const size_t after_version = source.find('\n');
  if (source.rfind("#version", 0) != 0 || after_version == std::string::npos)
    throw std::runtime_error("op counting: the shader does not begin with #version");
  const std::string stride = std::to_string(group_stride) + "u";
  return source.substr(0, after_version + 1) + "#define main rl_counted_main\n" +
         source.substr(after_version + 1) +
         "\n#undef main\n"
         "void rl_uncounted_group_gate() {\n"
         "  uvec2 group = uvec2(gl_FragCoord.xy) / uvec2(" +
         std::to_string(kWarpTileWidth) + "u, " + std::to_string(kWarpTileHeight) +
         "u);\n"
         "  if (group.x % " +
         stride + " != 0u || group.y % " + stride +
         " != 0u) discard;\n"
         "}\n"
         "void main() {\n"
         "  rl_uncounted_group_gate();\n"
         "  rl_counted_main();\n"
         "}\n";
}

}  // namespace

std::vector<uint32_t> fragment_spirv(const std::string& fragment_source) {
  initialise_glslang();
  const glslang_input_t input = fragment_input(fragment_source);
  std::unique_ptr<glslang_shader_t, ShaderDeleter> shader(glslang_shader_create(&input));
  glslang_shader_set_options(shader.get(),
                             GLSLANG_SHADER_AUTO_MAP_BINDINGS | GLSLANG_SHADER_AUTO_MAP_LOCATIONS);
  if (!glslang_shader_preprocess(shader.get(), &input))
    throw std::runtime_error(
        glslang_failure("preprocess", glslang_shader_get_info_log(shader.get())));
  if (!glslang_shader_parse(shader.get(), &input))
    throw std::runtime_error(glslang_failure("parse", glslang_shader_get_info_log(shader.get())));
  std::unique_ptr<glslang_program_t, ProgramDeleter> program(glslang_program_create());
  glslang_program_add_shader(program.get(), shader.get());
  if (!glslang_program_link(program.get(), GLSLANG_MSG_SPV_RULES_BIT) ||
      !glslang_program_map_io(program.get()))
    throw std::runtime_error(glslang_failure("link", glslang_program_get_info_log(program.get())));
  glslang_program_SPIRV_generate(program.get(), GLSLANG_STAGE_FRAGMENT);
  std::vector<uint32_t> words(glslang_program_SPIRV_get_size(program.get()));
  glslang_program_SPIRV_get(program.get(), words.data());
  return words;
}

std::string op_counting_glsl(const std::string& original_source, int group_stride) {
  const std::string fragment_source = with_group_gate(original_source, group_stride);
  // Translating takes about 0.1 s a program, once per process: the result is kept in the
  // precompute cache, keyed by the source and this form's version (bump it when the pass or
  // its classification changes).
  const std::string folder = precompute_cache_dir();
  const std::string version = "op-counting-form 3";
  const uint64_t key = fnv1a64(fragment_source);
  uint64_t length = 0;
  if (read_precompute_cache(folder, version + " length", key, &length, sizeof length) &&
      length < (64u << 20)) {
    std::string text(length, '\0');
    if (read_precompute_cache(folder, version + " text", key, text.data(), length)) return text;
  }
  const std::string text =
      glsl_of(without_assigned_locations(add_op_counters(fragment_spirv(fragment_source))));
  length = text.size();
  write_precompute_cache(folder, version + " text", key, text.data(), length);
  write_precompute_cache(folder, version + " length", key, &length, sizeof length);
  return text;
}

}  // namespace rl
