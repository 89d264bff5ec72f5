#pragma once
// GPU resources shared by every technique of one (scene, texture resolution): the relief and
// colour textures and the base geometry. Created once, reused by all rows that need them.
#include <memory>
#include <vector>

#include <epoxy/gl.h>

#include "gpu/gpu_cell_complex.h"
#include "gpu/gpu_heightfield_faces.h"
#include "relief/relief_map.h"
#include "scene/scene.h"

namespace rl {

// A 2D texture of floats, bilinear and repeating, no mipmaps: how the relief map and what is
// read beside it (colour, AO, a packed copy) are uploaded, the surface the truth reconstructs.
// `format`: GL_RGBA or GL_RED of `texels`, stored as `internal_format`.
GLuint make_texture(int w, int h, GLenum internal_format, GLenum format, const float* texels);

class GpuRelief {
 public:
  // RGBA8 when the map is quantised, else RGBA32F. `meta_layers`: also the layers of the map's
  // meta-relief, for shaders that combine them per fetch (units 10 + i), and their AO maps
  // where it has them (units 18 + i).
  explicit GpuRelief(const ReliefMap& map, bool meta_layers = false);
  ~GpuRelief();
  GpuRelief(const GpuRelief&) = delete;
  GpuRelief& operator=(const GpuRelief&) = delete;
  // Also binds the AO map, where the map has one, to unit 8 (harness/glsl/ambient_occlusion.glsl),
  // a cell complex's textures to units 4-7 (GpuCellComplex::bind), and a heightfield object's
  // faces to units 4-5 (GpuHeightfieldFaces::bind).
  void bind(GLuint relief_unit = 0, GLuint color_unit = 1) const;
  size_t bytes() const { return bytes_; }
  // A cell complex's textures (the map's `cells`), else null.
  const GpuCellComplex* cells() const { return cells_.get(); }
  // A heightfield object's faces (the map's `faces`), else null.
  const GpuHeightfieldFaces* faces() const { return faces_.get(); }

 private:
  GLuint relief_ = 0, color_ = 0, ambient_ = 0;
  std::vector<GLuint> meta_layers_, meta_ambient_;
  std::unique_ptr<GpuCellComplex> cells_;
  std::unique_ptr<GpuHeightfieldFaces> faces_;
  size_t bytes_ = 0;
};

class GpuBase {
 public:
  explicit GpuBase(const BaseGeometry& geometry);
  ~GpuBase();
  GpuBase(const GpuBase&) = delete;
  GpuBase& operator=(const GpuBase&) = delete;
  void draw() const;

 private:
  GLuint vao_ = 0, vbo_ = 0, ibo_ = 0;
  GLsizei index_count_ = 0;
};

}  // namespace rl
