#pragma once
// Relief mapping on cubic cell complexes (Apaza & Andujar, Section 3): a closed mesh encoded as
// an N x N x N grid of cubic cells over its bounding cube, one distance map per domain face.
//
// Everything here lives in the cube's texture space (u, v, depth) in [0, 1]^3 (the frame of
// cell_frame()); a cell's local coordinates q are in [0, 1]^3 too. Faces of a cell are numbered
// f = 2 * axis + side: 0 = -u, 1 = +u, 2 = -v, 3 = +v, 4 = -depth, 5 = +depth. A face's map is
// indexed by its two other axes in cyclic order: (q[(axis + 1) % 3], q[(axis + 2) % 3]).
//
// The encoded surface: a point q of a grey cell is projected by the cell's projection onto a
// domain face at P'; the face's texel there stores d, the distance from P' to the first surface
// crossing along the projection line, as a fraction of the line's length L inside the cell (1:
// no crossing), and whether P' itself is inside the object (only possible on an interior grey
// cell's faces). q is inside when that flag differs from |q - P'| > d L.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/triangle_mesh.h"
#include "relief/mesh_bake.h"

namespace rl {

enum class CellState : uint8_t { White = 0, Grey = 1, Black = 2 };

// Section 3.2's ten base cases of a grey cell's internal/external faces, up to rotation.
enum class CellCase : uint8_t { C0, C1, C2a, C2b, C3a, C3b, C4a, C4b, C5, C6 };
const char* cell_case_name(CellCase c);  // "0", "1", "2a", ...

struct CellProjection {
  enum class Type : uint8_t { Perspective = 0, Axial = 1, Planar = 2, Parallel = 3 };
  Type type = Type::Perspective;
  // Perspective: the centre of projection. Axial: a point of the axis. Planar: the plane passes
  // through it (its coordinate along `axis`). Cell-local coordinates, each 0, 0.5 or 1.
  glm::dvec3 point{0.5};
  // Axial: the axis' direction (0, 1, 2). Planar: the plane's normal axis. Parallel: the face
  // (0-5) whose outward normal is the direction of projection.
  int axis = 0;
};
const char* projection_type_name(CellProjection::Type t);

// A grey cell's configuration: bit f of `internal_mask` is set when face f is internal (shared
// with a grey or black cell), clear when external (shared with a white cell or the outside).
struct CellConfiguration {
  CellCase base_case;
  CellProjection projection;
  uint8_t domain_mask;  // faces the cell projects onto: external faces, or all six (case 6)
};
CellConfiguration configure_cell(uint8_t internal_mask);

// Where the projection line through cell-local point q meets the cell's boundary.
struct CellLine {
  int face = -1;          // the face it exits through (-1: q is the projection's centre)
  glm::dvec3 on_face{0};  // P', cell-local
  glm::dvec3 inner{0};    // the line's other end: centre, axis foot, plane point, far face
  double length = 0;      // |P' - inner|
  double along = 0;       // |P' - q|
};
// `domain_mask` breaks ties where q's line leaves through an edge or corner.
CellLine project_in_cell(const CellProjection& p, uint8_t domain_mask, const glm::dvec3& q);
// The line of the texel at face coordinates (s, t) of face `face`.
CellLine face_line(const CellProjection& p, int face, glm::dvec2 st);
// Cell-local point of face `face` at face coordinates (s, t), and back.
glm::dvec3 face_point(int face, glm::dvec2 st);
glm::dvec2 face_coords(int face, const glm::dvec3& q);

struct CellComplexOptions {
  int grid = 0;             // N; 0: chosen by the occluded-fragment ratio (Section 3.3.3)
  int resolution = 64;      // texels per side of every domain face's maps
  int distance_bits = 16;   // 16 (Table 1) or 8
  double threshold = 0.05;  // auto grid: the occluded-fragment ratio to get below
  int grid_max = 16;        // auto grid: N_max
};
inline constexpr int kMaxCellGrid = 32;
// The albedo of a mesh without colours (as the heightfield bake of a mesh uses).
inline const glm::vec3 kCellAlbedo(0.78f, 0.74f, 0.70f);

// One step of the automatic grid choice.
struct GridTrial {
  int grid = 0;
  double occluded_ratio = 0;  // occluded fragments / all fragments
  long grey_cells = 0, domain_faces = 0;
  double construction_ms = 0;  // classification + sampling at this N
};

class CellComplex {
 public:
  struct Cell {
    CellState state = CellState::White;
    uint8_t internal_mask = 0;
    CellConfiguration config{};
    int first_face = -1;  // index of its first domain face's maps (grey cells)
  };
  struct Stats {
    long grey_cells = 0, black_cells = 0, white_cells = 0, border_grey = 0, interior_grey = 0;
    long domain_faces = 0;
    std::array<long, 10> cases{};  // grey cells per base case
    // Fragments (surface crossings of the texels' projection lines inside their cells), those
    // hidden behind a first crossing (Section 3.3.3's occluded fragments), and texels whose
    // line crossed more than once (what a single distance per texel loses).
    long fragments = 0, occluded_fragments = 0, multi_crossing_texels = 0;
    // Non-grey regions whose inside/outside parity votes disagreed (an open or non-manifold
    // mesh): resolved by the majority.
    long ambiguous_regions = 0;
    long mesh_triangles = 0;
    long degenerate_triangles = 0;          // zero-area triangles skipped
    double classify_ms = 0, sample_ms = 0;  // of this grid
    // With an automatic grid: classification and sampling of every grid tried, this one's
    // included (what choosing N costs); else classify_ms + sample_ms.
    double construction_ms = 0;
    std::vector<GridTrial> trials;  // the automatic grid choice's steps, if any
    bool from_cache = false;        // read from the precompute cache (times are the build's)
    double occluded_ratio() const {
      return fragments ? double(occluded_fragments) / double(fragments) : 0.0;
    }
  };

  // Builds the complex of `mesh` (already in texture space, inside [0, 1]^3).
  static CellComplex build(const TriangleMesh& mesh, const CellComplexOptions& options);
  // The same complex with its distance and normal maps sampled elsewhere (the GPU's, Section
  // 3.3.2: gpu/cell_gpu_sampling.h), each res x res per domain face like distance(): d in
  // [0, 1) where a surface point projects onto the texel, 1 where none does, and that point's
  // unit normal. A line that misses the surface keeps the CPU's d (0 for one inside all along);
  // a texel without a point takes its neighbours' normal, as build() dilates them. Throws
  // std::invalid_argument when the maps are not the complex's size.
  CellComplex with_sampled_maps(const std::vector<float>& distance,
                                const std::vector<glm::vec3>& normal) const;
  // The complex as bytes (everything but the mesh), and back with its mesh; false when the
  // bytes are not a complex of this version.
  std::vector<uint8_t> serialize() const;
  static bool deserialize(const std::vector<uint8_t>& bytes, TriangleMesh mesh, CellComplex& out);

  int grid() const { return n_; }
  int resolution() const { return res_; }
  int distance_bits() const { return bits_; }
  const Cell& cell(int i, int j, int k) const { return cells_[index(i, j, k)]; }
  const std::vector<Cell>& cells() const { return cells_; }
  size_t index(int i, int j, int k) const { return (size_t(k) * n_ + j) * n_ + i; }
  const Stats& stats() const { return stats_; }
  // The mesh it encodes, in texture space (the baseline draws it; the truth traces the file).
  const TriangleMesh& mesh() const { return mesh_; }
  // Domain face `i`: its cell and face number.
  struct DomainFace {
    int cell = 0, face = 0;
  };
  const std::vector<DomainFace>& domain_faces() const { return faces_; }
  // The maps, res x res per domain face, row-major (t rows of s), face after face.
  const std::vector<uint16_t>& distance() const { return distance_; }  // d as a fraction of L
  const std::vector<uint8_t>& face_inside() const { return face_inside_; }
  // Surface crossings of each texel's projection line inside its cell (capped at 255): 0 where
  // the line misses the surface, > 1 where sheets behind the first are lost.
  const std::vector<uint8_t>& crossings() const { return crossings_; }
  const std::vector<glm::vec3>& normal() const { return normal_; }  // texture-space, unit
  const std::vector<glm::vec3>& color() const { return color_; }
  double distance_scale() const { return bits_ == 16 ? 65535.0 : 255.0; }
  // Bytes of the maps as uploaded (distance + flag, normal, colour, cell table).
  size_t gpu_bytes() const;
  // Bytes of the distances alone at distance_bits (what the paper's Table 1 counts).
  size_t distance_bytes() const { return faces_.size() * size_t(res_) * res_ * size_t(bits_ / 8); }

  // The encoded surface at a texture-space point: inside the object? (bilinear distances,
  // clamped to the face's texel centres, as the shader samples them).
  bool encoded_inside(const glm::dvec3& p) const;
  // The domain face index and its coordinates that p projects to, or -1 (white, black, outside).
  struct Lookup {
    int face_index = -1;
    glm::dvec2 st{0};
    CellLine line;
  };
  Lookup lookup(const glm::dvec3& p) const;
  // Bilinear sample of face `face_index`'s distance fraction (and inside flag, nearest).
  double sample_distance(int face_index, glm::dvec2 st, bool* inside_flag = nullptr) const;
  glm::dvec3 sample_normal(int face_index, glm::dvec2 st) const;
  glm::dvec3 sample_color(int face_index, glm::dvec2 st) const;

 private:
  friend struct CellComplexBuilder;  // the construction's stages (cell_complex.cpp)
  int n_ = 1, res_ = 64, bits_ = 16;
  std::vector<Cell> cells_;
  std::vector<DomainFace> faces_;
  std::vector<uint16_t> distance_;
  std::vector<uint8_t> face_inside_, crossings_;
  std::vector<glm::vec3> normal_, color_;
  Stats stats_;
  TriangleMesh mesh_;
};

// Geometry-based rendering (Section 3.5.1): the distance maps at mip level `lod` (texels
// averaged in 2^lod x 2^lod blocks over the lines that meet the surface, valid where at least
// half do) unprojected
// along their projection lines, a vertex per texel corner (the mean of the valid texels around
// it, so a face's triangles reach its edges) and two triangles per texel. Texture space;
// normals and colours per vertex from the maps. A triangle with an edge longer than
// `max_edge_texels` texels of its level joins two sheets across a depth discontinuity and is
// dropped.
struct CellMesh {
  std::vector<glm::vec3> position, normal, color;
  std::vector<glm::uvec3> triangles;
};
CellMesh reconstruct_cell_mesh(const CellComplex& cells, int lod, double max_edge_texels);

// The mesh's bounding cube as a texture-space frame: u, v along the two axes after `up`
// (cyclic), depth down `up`, the same length per unit on all three, padded by `margin` of the
// side on every face so no surface lies on the cube's boundary.
BakeFrame cell_frame(const TriangleMesh& mesh, int up, double margin = 0.02);
// The mesh's vertices in the frame's texture space.
TriangleMesh to_frame(const TriangleMesh& mesh, const BakeFrame& frame);
// Each triangle split into four at its edges' midpoints, `times` times (4^times as many
// triangles, the same surface): a stand-in for a finer scan of the same object.
TriangleMesh subdivide_midpoints(const TriangleMesh& mesh, int times);

// Exact test of a triangle against an axis-aligned box (separating axes, Akenine-Moeller),
// closed box: touching counts.
bool triangle_overlaps_box(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                           const glm::dvec3& box_lo, const glm::dvec3& box_hi);

}  // namespace rl
