#include "gl/shader_library.h"

#include <algorithm>
#include <regex>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/hash.h"
#include "gl/context.h"
#include "gl/embedded_files.h"
#include "gl/op_count_buffer.h"
#include "gl/op_counting.h"

namespace rl {
namespace {

const std::string& embedded(const std::string& path, const std::string& from) {
  const auto& files = embedded_files();
  auto it = files.find(path);
  if (it == files.end())
    throw GlError("GLSL file '" + path + "' not found" +
                  (from.empty() ? "" : " (included from " + from + ")") +
                  "; is it under harness/glsl/ or techniques/ and was CMake re-run?");
  return it->second;
}

void expand(const std::string& path, const std::string& from, ComposedSource& out,
            std::set<std::string>& seen) {
  if (!seen.insert(path).second) return;  // each file once: includes act as guarded headers
  const int id = static_cast<int>(out.files.size());
  out.files.push_back(path);
  std::istringstream in(embedded(path, from));
  std::string line;
  int line_no = 0;
  static const std::regex include_re(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
  out.text += "#line 1 " + std::to_string(id) + "\n";
  while (std::getline(in, line)) {
    ++line_no;
    std::smatch m;
    if (std::regex_match(line, m, include_re)) {
      expand(m[1].str(), path + ":" + std::to_string(line_no), out, seen);
      out.text += "#line " + std::to_string(line_no + 1) + " " + std::to_string(id) + "\n";
    } else {
      out.text += line + "\n";
    }
  }
}

// The info log of a shader (glGetShaderiv, glGetShaderInfoLog) or a program (the Program pair).
std::string info_log(GLuint object, void (*get_iv)(GLuint, GLenum, GLint*),
                     void (*get_log)(GLuint, GLsizei, GLsizei*, GLchar*)) {
  GLint len = 0;
  get_iv(object, GL_INFO_LOG_LENGTH, &len);
  std::string log(static_cast<size_t>(std::max(len, 1)), '\0');
  get_log(object, len, nullptr, log.data());
  return log;
}

GLuint compile(GLenum stage, const ComposedSource& src, const std::string& owner) {
  GLuint shader = glCreateShader(stage);
  const char* text = src.text.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = info_log(shader, glGetShaderiv, glGetShaderInfoLog);
    glDeleteShader(shader);
    const char* name = stage == GL_VERTEX_SHADER     ? "vertex"
                       : stage == GL_GEOMETRY_SHADER ? "geometry"
                                                     : "fragment";
    throw GlError("technique '" + owner + "': " + name + " shader failed to compile:\n" +
                  map_glsl_log(log, src.files));
  }
  return shader;
}

// The op-counting form of a fragment source whose fragments write their counts; a pass that
// writes none (a plain object's, say) counts nothing, as in the G-buffer render's fetch counts.
std::string counting_form(const std::string& text, const std::string& owner, int group_stride) {
  if (text.find("rl_count_fragment") == std::string::npos) return text;
  try {
    return op_counting_glsl(text, group_stride);
  } catch (const std::runtime_error& e) {
    throw GlError("technique '" + owner + "': " + e.what());
  }
}

// While alive and `quiet`, the driver's compiler messages are not reported: the op-counting form
// is GLSL that SPIRV-Cross wrote, and its warnings (locals it declares before assigning, say)
// are not the technique's. Its errors still throw, from the compile log.
struct QuietCompiler {
  explicit QuietCompiler(bool silence) : quiet(silence) { set(GL_FALSE); }
  ~QuietCompiler() { set(GL_TRUE); }
  void set(GLboolean report) const {
    if (quiet)
      glDebugMessageControl(GL_DEBUG_SOURCE_SHADER_COMPILER, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr,
                            report);
  }
  bool quiet;
};

// `g`, the geometry stage, may be 0 (none).
GLuint link(GLuint v, GLuint g, GLuint f, const std::string& owner, const ComposedSource& fs) {
  GLuint program = glCreateProgram();
  for (GLuint stage : {v, g, f})
    if (stage) glAttachShader(program, stage);
  glLinkProgram(program);
  for (GLuint stage : {v, g, f})
    if (stage) glDeleteShader(stage);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = info_log(program, glGetProgramiv, glGetProgramInfoLog);
    glDeleteProgram(program);
    throw GlError("technique '" + owner + "': program " + fs.files.back() + " failed to link:\n" +
                  map_glsl_log(log, fs.files));
  }
  return program;
}

std::string cache_key(const ProgramDesc& d) {
  std::string key = d.owner + "|" + d.vertex_file + "|" + d.geometry_file;
  for (const auto& f : d.fragment_files) key += "|" + f;
  for (const auto& [k, v] : d.defines) key += "|" + k + "=" + v;
  return key;
}

std::vector<ProgramUses*>& active_recorders() {
  static std::vector<ProgramUses*> recorders;
  return recorders;
}

}  // namespace

ProgramUses::ProgramUses() {
  active_recorders().push_back(this);
}

ProgramUses::~ProgramUses() {
  auto& r = active_recorders();
  r.erase(std::find(r.begin(), r.end(), this));
}

void ProgramUses::note(const ProgramDesc& desc) {
  if (active_recorders().empty()) return;
  const std::string key = cache_key(desc);
  for (ProgramUses* r : active_recorders()) r->programs_.emplace(key, desc);
}

std::string program_digest(const ProgramDesc& desc) {
  static std::map<std::string, std::string> memo;  // embedded files never change once loaded
  const std::string key = cache_key(desc);
  if (auto it = memo.find(key); it != memo.end()) return it->second;
  std::string text = compose_glsl({desc.vertex_file}, desc.defines).text;
  if (!desc.geometry_file.empty())
    text += "\n--geometry--\n" + compose_glsl({desc.geometry_file}, desc.defines).text;
  text += "\n--fragment--\n" + compose_glsl(desc.fragment_files, desc.defines).text;
  return memo[key] = hex64(fnv1a64(text));
}

ComposedSource compose_glsl(const std::vector<std::string>& files, const Defines& defines) {
  ComposedSource out;
  std::string header = "#version 450 core\n";
  for (const auto& [k, v] : defines) header += "#define " + k + " " + v + "\n";
  std::set<std::string> seen;
  for (const std::string& file : files) expand(file, "", out, seen);
  out.text = header + out.text;
  return out;
}

std::string map_glsl_log(const std::string& log, const std::vector<std::string>& files) {
  auto name = [&](const std::string& id) {
    size_t i = std::stoul(id);
    return i < files.size() ? files[i] : "source " + id;
  };
  std::string out;
  std::istringstream in(log);
  std::string line;
  static const std::regex mesa(R"(^(\d+):(\d+)\((\d+)\):(.*)$)");
  static const std::regex nvidia(R"(^(\d+)\((\d+)\)\s*:(.*)$)");
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, m, mesa))
      out += name(m[1]) + ":" + m[2].str() + ":" + m[3].str() + ":" + m[4].str() + "\n";
    else if (std::regex_match(line, m, nvidia))
      out += name(m[1]) + ":" + m[2].str() + ":" + m[3].str() + "\n";
    else if (!line.empty() && line[0] != '\0')
      out += line + "\n";
  }
  return out;
}

ShaderLibrary& ShaderLibrary::shared() {
  GlContext::shared();  // programs live in the shared context
  static ShaderLibrary library;
  return library;
}

ShaderLibrary::Entry& ShaderLibrary::entry(const ProgramDesc& plain) {
  ProgramUses::note(plain);
  ProgramDesc desc = plain;
  // The stride is part of the key: a program gated for one stride is not another's.
  if (OpCountingScope::active())
    desc.defines["RL_COUNT_OPS"] = std::to_string(OpCountingScope::group_stride());
  const std::string key = cache_key(desc);
  auto it = programs_.find(key);
  if (it != programs_.end()) return it->second;
  ComposedSource vs = compose_glsl({desc.vertex_file}, desc.defines);
  ComposedSource fs = compose_glsl(desc.fragment_files, desc.defines);
  const bool counting = desc.defines.count("RL_COUNT_OPS") > 0;
  if (counting) fs.text = counting_form(fs.text, desc.owner, OpCountingScope::group_stride());
  GLuint v = compile(GL_VERTEX_SHADER, vs, desc.owner), g = 0, f = 0;
  try {
    if (!desc.geometry_file.empty())
      g = compile(GL_GEOMETRY_SHADER, compose_glsl({desc.geometry_file}, desc.defines), desc.owner);
    QuietCompiler quiet(counting);
    f = compile(GL_FRAGMENT_SHADER, fs, desc.owner);
  } catch (...) {
    glDeleteShader(v);
    if (g) glDeleteShader(g);
    throw;
  }
  Entry e;
  e.program = link(v, g, f, desc.owner, fs);
  e.fragment_source = fs.text;
  return programs_.emplace(key, std::move(e)).first->second;
}

GLuint ShaderLibrary::program(const ProgramDesc& desc) {
  return entry(desc).program;
}

const std::string& ShaderLibrary::fragment_source(const ProgramDesc& desc) {
  return entry(desc).fragment_source;
}

}  // namespace rl
