#pragma once
#include <string>
#include <vector>

namespace rl {

// A file a scene reads, in the role it is read in ("relief depth (channel 0)", "relief normal
// (RGB normal; depth from alpha)", "base mesh", "object 2 mesh", ...), with its content digest
// (core/code_digest.h: file_digest). A row's provenance names them (run/cell_provenance.h).
struct SceneInput {
  std::string role, path, digest;
  bool image = false;  // decoded by the image module (relief/image_backend.h); a mesh is not
};

// Whether any of `inputs` is an image: only then does the image module decode anything of the
// scene, and only then is it loaded for the scene (it costs a process about 0.5 s to load).
inline bool reads_images(const std::vector<SceneInput>& inputs) {
  for (const SceneInput& in : inputs)
    if (in.image) return true;
  return false;
}

}  // namespace rl
