#pragma once
// An object from several heightfields as its techniques read it (relief/heightfield_faces.h):
// the faces' relief maps (rgb: normal in the face's u, v, up; a: depth) and colour maps as two
// array textures, one layer per face, bilinear and clamped to the edge (a face does not repeat);
// harness/glsl/heightfield_faces.glsl decodes them.
#include <epoxy/gl.h>

#include "relief/heightfield_faces.h"

namespace rl {

class GpuHeightfieldFaces {
 public:
  explicit GpuHeightfieldFaces(const HeightfieldFaces& faces);
  ~GpuHeightfieldFaces();
  GpuHeightfieldFaces(const GpuHeightfieldFaces&) = delete;
  GpuHeightfieldFaces& operator=(const GpuHeightfieldFaces&) = delete;
  void bind() const;  // units 4 (relief), 5 (colour)
  size_t bytes() const { return bytes_; }

 private:
  GLuint relief_ = 0, color_ = 0;
  size_t bytes_ = 0;
};

// rl_face_count, rl_face_from_cube[] and rl_face_cop: what heightfield_faces.glsl maps a cube
// point into each face's texture space with.
void set_heightfield_faces_uniforms(GLuint program, const HeightfieldFaces& faces);

}  // namespace rl
