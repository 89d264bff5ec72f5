#pragma once
// A cell complex's textures as the cell-complex techniques read them (Apaza & Andujar,
// Section 3.4): the cell table (a 3D RG32UI texture, one texel per cell: state, projection and
// domain faces; first domain face), and the domain faces' distance, normal and colour maps in
// array textures. Faces are tiled tiles x tiles per array layer where there are more faces than
// layers (GL guarantees 2048); techniques/cell_complex/cell_complex_common.glsl decodes both.
#include <epoxy/gl.h>

#include "relief/cell_complex.h"
#include "scene/scene.h"

namespace rl {

class GpuCellComplex {
 public:
  explicit GpuCellComplex(const CellComplex& cells);
  ~GpuCellComplex();
  GpuCellComplex(const GpuCellComplex&) = delete;
  GpuCellComplex& operator=(const GpuCellComplex&) = delete;
  // Units 4 (table), 5 (distance + inside flag), 6 (normal), 7 (colour).
  void bind() const;
  int tiles() const { return tiles_; }  // faces per layer along each side
  size_t bytes() const { return bytes_; }

  // The table texel of a grey cell: state | type << 2 | axis << 4 | point << 7 | domain << 12.
  static uint32_t pack_cell(const CellComplex::Cell& c);

 private:
  GLuint table_ = 0, distance_ = 0, normal_ = 0, color_ = 0;
  int tiles_ = 1;
  size_t bytes_ = 0;
};

// The uniforms both cell-complex techniques read: rl_world_from_texture (the cube's texture
// space placed by the scene's planar base), rl_normal_from_texture, rl_eye_texture,
// rl_cell_albedo, and the table's (set_cell_table_uniforms).
void set_cell_complex_uniforms(GLuint program, const SceneDesc& scene, const Camera& camera,
                               const CellComplex& cells, const GpuCellComplex& gpu);
// rl_cell_n, rl_cell_res, rl_cell_tiles: what cell_complex_common.glsl decodes the table with.
void set_cell_table_uniforms(GLuint program, const CellComplex& cells, const GpuCellComplex& gpu);

}  // namespace rl
