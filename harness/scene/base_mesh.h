#pragma once
// Base meshes a relief is mapped onto (book chapter 5: relief mapping of arbitrary polygonal
// surfaces, and its silhouette section): generated plane, cube, sphere and torus with uv
// parameterisations, the Utah teapot, and OBJ/PLY files with uvs. Every vertex carries the
// tangent frame of its uv mapping scaled by the mapping (world length per unit of u and v: the
// chapter's tangent.w and binormal.w) and the quadric curvature (A, B) of its one-ring
// (Listing 5.8), which the silhouette technique bends its rays with.
#include <functional>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/triangle_mesh.h"
#include "scene/scene.h"

namespace rl {

// A parametric patch of a generated base: the exact surface over a uv rectangle. The rendered
// mesh samples it at segments_u x segments_v quads; the truth samples it at texel density.
struct SurfaceChart {
  glm::dvec2 uv_min{0}, uv_max{1};
  int segments_u = 1, segments_v = 1;
  std::function<void(const glm::dvec2& uv, glm::dvec3& position, glm::dvec3& normal)> eval;
};

struct BaseMesh {
  std::vector<glm::dvec3> position, normal;  // world space, unit normals
  std::vector<glm::dvec2> uv;                // texture coordinates, tiling included
  std::vector<glm::dvec3> dpdu, dpdv;        // unit tangents scaled by the mapping
  std::vector<glm::dvec2> curvature;         // quadric (A, B) along dpdu, dpdv
  std::vector<glm::uvec3> triangles;         // counter-clockwise seen from outside
  std::vector<SurfaceChart> charts;          // generated bases: the exact surface; files: none
  double radius = 0;                         // bounding sphere about the origin
};

// The base of `desc`, fitted into a sphere of diameter `size` about the origin, uvs repeated
// `tile` times. Throws ConfigError for unknown kinds, and for mesh files without uvs unless
// `require_uvs` is false (plain objects), when they get the teapot's cylindrical projection.
BaseMesh make_base_mesh(const BaseDesc& desc, double size, double tile, bool require_uvs = true);

// A base mesh file's own uvs map a relief: each within +-1024 (float precision), and some
// triangle of nonzero area in texture space. Throws ConfigError naming the file.
void check_base_uvs(const TriangleMesh& file);

// True for the generated kinds (an exact parametric surface), false for mesh files.
inline bool has_charts(const BaseDesc& desc) {
  return desc.kind != "teapot" && desc.kind != "file";
}

// World size of one texel of the scene's map at texture resolution `res` (size_at) on its base
// (planar: exact; curved: the mean mapping scale over the base's vertices and both axes), the
// unit of position errors in texels; a cell complex's is kCellMetricTexels of its cube.
double texel_world(const SceneDesc& scene, int res);
double texel_world(const BaseMesh& mesh, const MapSize& size);

// The mesh as the shaders receive it.
BaseGeometry base_geometry(const BaseMesh& mesh);

// Tangent frames of the uv mapping: per triangle the solution of dP = dpdu du + dpdv dv (the
// core of Lengyel's method and of MikkTSpace), accumulated at the vertices weighted by corner
// angle; the direction of u is orthogonalised against the normal, v completes a frame with
// the mapping's handedness, and the mapping scale is the angle-weighted mean length of the
// per-triangle axes (chapter 5: "average the length of each u and v texture axis").
void compute_tangent_frames(BaseMesh& mesh);

// The unit frame of a uv mapping at a point with unit normal n and mapping axes du, dv: t along
// du orthogonalised against n (any tangent where du vanishes), b = +-(n x t) with dv's side.
void uv_frame(const glm::dvec3& n, const glm::dvec3& du, const glm::dvec3& dv, glm::dvec3& t,
              glm::dvec3& b);

// The quadric z = -(A x^2 + B y^2) fitted by least squares to points (x, y, z) in a vertex's
// tangent frame (Listing 5.8; z along the outward normal, so A, B > 0 where the surface is
// convex: the chapter's "positive curvature"). Fewer than 3 points give (0, 0) as in the
// listing; rank-deficient rings (collinear neighbours) the minimum-norm solution, which is
// finite (Eigen's complete orthogonal decomposition).
glm::dvec2 fit_quadric(const std::vector<glm::dvec3>& ring);

// Per-vertex curvature from each vertex's one-ring, vertices welded by position so that uv
// seams and poles see their whole ring.
void compute_curvature(BaseMesh& mesh);

// The fitted curvature against the exact surface's, where a generated base has a closed form
// (Figure 5.28's curvature of the torus; the sphere): per vertex the exact quadric is A* = k1 / 2
// along dpdu, B* = k2 / 2 along dpdv (the uv frames of both run along principal directions).
struct CurvatureFitError {
  // Per vertex max(|A - A*|, |B - B*|) / max(|A*|, |B*|), in %: the mean and the largest.
  double mean_pct = 0, max_pct = 0;
  // Of the coefficients that are not planar (|A*| or |B*| at least 5% of the vertex's larger),
  // the share whose fitted sign is the exact one: Figure 5.28's red and blue.
  double sign_match_pct = 0;
};

// Empty where no closed form is known here: plane and cube (flat but at their edges, where no
// quadric holds), the teapot and mesh files.
std::optional<CurvatureFitError> curvature_fit_error(const BaseDesc& desc, const BaseMesh& mesh);

}  // namespace rl
