#pragma once
// GLSL composition and caching. A program is described by its owner (a technique name, for
// error messages), its stage files and its #defines; files are resolved from the sources
// embedded in the binary, with `#include "path"` expanded recursively (once per file) and
// `#line` directives so compile errors name the real file and line. Programs are cached per
// (owner, files, defines): a sweep compiles each variant once.
#include <map>
#include <string>
#include <vector>

#include <epoxy/gl.h>

namespace rl {

using Defines = std::map<std::string, std::string>;

struct ProgramDesc {
  std::string owner;                        // e.g. "relief"
  std::string vertex_file;                  // e.g. "harness/glsl/base.vert"
  std::vector<std::string> fragment_files;  // composed in order, e.g. {technique, main}
  Defines defines;
  std::string geometry_file;  // optional, e.g. "harness/glsl/cell_sampling_geom.glsl"
};

struct ComposedSource {
  std::string text;
  std::vector<std::string> files;  // source-string number -> file path, for error messages
};

// Expands includes in each file, in order, and prepends `#version 450 core` and the defines.
ComposedSource compose_glsl(const std::vector<std::string>& files, const Defines& defines);
// Rewrites "0:12(5): error" (Mesa) and "0(12) : error" (NVIDIA) to "file:12: error".
std::string map_glsl_log(const std::string& log, const std::vector<std::string>& files);

// The digest of what `desc` compiles (16 hex digits): each stage's source after its includes,
// with its defines, composed from the sources embedded now, without a GL context. A stored
// row names the programs it was drawn by, so an edited shader re-measures the rows that drew
// with it and no other. Throws GlError as compose_glsl does for a missing file.
std::string program_digest(const ProgramDesc& desc);

// While alive, records every program requested through ShaderLibrary, compiled or found in
// its cache, as its caller described it (before the op-counting define): what a cell's frame
// was drawn with. Recorders nest; each sees the requests made during its own life.
class ProgramUses {
 public:
  ProgramUses();
  ~ProgramUses();
  ProgramUses(const ProgramUses&) = delete;
  ProgramUses& operator=(const ProgramUses&) = delete;
  // By the library's cache key, so a program requested for every frame is listed once.
  const std::map<std::string, ProgramDesc>& programs() const { return programs_; }
  static void note(const ProgramDesc& desc);

 private:
  std::map<std::string, ProgramDesc> programs_;
};

class ShaderLibrary {
 public:
  static ShaderLibrary& shared();
  // Compiles and links on first use; throws GlError naming owner, file and line on failure.
  GLuint program(const ProgramDesc& desc);
  // The composed fragment source of a cached program (for tests that inspect what was compiled).
  const std::string& fragment_source(const ProgramDesc& desc);
  size_t compiled_count() const { return programs_.size(); }

 private:
  struct Entry {
    GLuint program = 0;
    std::string fragment_source;
  };
  Entry& entry(const ProgramDesc& desc);
  std::map<std::string, Entry> programs_;
};

}  // namespace rl
