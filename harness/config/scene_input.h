#pragma once
#include <string>

namespace rl {

// A file a scene reads, in the role it is read in ("relief depth (channel 0)", "relief normal
// (RGB normal; depth from alpha)", "base mesh", "object 2 mesh", ...), with its content digest
// (core/code_digest.h: file_digest). A row's provenance names them (run/cell_provenance.h).
struct SceneInput {
  std::string role, path, digest;
};

}  // namespace rl
