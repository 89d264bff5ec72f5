#include "relief/heightfield_faces.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/columns.h"

namespace rl {
namespace {

const ColumnDeclaration face_columns(
    "relief (heightfield faces)",
    {ColumnSpec{"face_count", "maps", "heightfield maps of an object from several heightfields"}
         .neither_better()});

}  // namespace

std::vector<int> face_set(int count) {
  switch (count) {
    case 1:
      return {kTopFace};
    case 2:
      return {kTopFace, 5};
    case 3:
      return {kTopFace, 1, 3};
    case 6:
      return {kTopFace, 5, 0, 1, 2, 3};
  }
  throw std::invalid_argument("a heightfield object has 1, 2, 3 or 6 faces, not " +
                              std::to_string(count));
}

glm::dmat3 face_from_cube(int face) {
  if (face < 0 || face >= kCubeFaces)
    throw std::invalid_argument("no cube face " + std::to_string(face));
  const int axis = face / 2;
  glm::dvec3 inward(0);
  inward[axis] = face % 2 ? -1.0 : 1.0;  // side 1 lies at coordinate 1: look towards 0
  // The face's u: the next axis in cyclic order (u for the top), v completes a right-handed
  // frame (u, v, inward): the face's image is not mirrored.
  glm::dvec3 u(0);
  u[axis == 2 ? 0 : (axis + 1) % 3] = 1;
  if (axis == 2 && face % 2) u = -u;  // the bottom: a rotation about v, not a mirror
  const glm::dvec3 v = glm::cross(inward, u);
  // glm is column-major: the rows u, v, inward are the columns of the transpose.
  return glm::transpose(glm::dmat3(u, v, inward));
}

glm::dvec3 HeightfieldFaces::face_texture(int k, const glm::dvec3& cube) const {
  const glm::dvec3 a = face_from_cube(faces[size_t(k)]) * (cube - 0.5) + 0.5;
  return projection.texture_from_affine(a);
}

double HeightfieldFaces::behind(int k, const glm::dvec3& cube) const {
  const glm::dvec3 t = face_texture(k, cube);
  if (t.x < 0 || t.x > 1 || t.y < 0 || t.y > 1) return std::numeric_limits<double>::infinity();
  const ReliefMap& m = maps[size_t(k)];
  const double d = m.sample_relief_clamped(t.x, t.y).a;
  if (d >= kEmptyFaceDepth) return -std::numeric_limits<double>::infinity();
  return t.z - d;
}

bool HeightfieldFaces::inside(const glm::dvec3& cube, double tolerance) const {
  for (int k = 0; k < count(); ++k)
    if (behind(k, cube) < -tolerance) return false;
  return true;
}

int HeightfieldFaces::surface_face(const glm::dvec3& cube) const {
  std::vector<double> b(static_cast<size_t>(count()));
  double nearest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < count(); ++k) nearest = std::min(nearest, b[size_t(k)] = behind(k, cube));
  int best = 0;
  double best_facing = -2;
  for (int k = 0; k < count(); ++k) {
    if (!(b[size_t(k)] <= nearest + 1.0 / resolution())) continue;
    const glm::dvec3 t = face_texture(k, cube);
    const ReliefMap& m = maps[size_t(k)];
    const double facing = m.sample_relief_clamped(t.x, t.y).b * 2 - 1;
    if (facing > best_facing) best_facing = facing, best = k;
  }
  return best;
}

glm::dvec3 HeightfieldFaces::cube_normal(int k, const glm::dvec3& cube) const {
  const glm::dvec3 t = face_texture(k, cube);
  const ReliefMap& m = maps[size_t(k)];
  const glm::dvec3 s = glm::dvec3(m.sample_relief_clamped(t.x, t.y)) * 2.0 - 1.0;
  // Stored in the face's (u, v, up); its texture space points depth down.
  const glm::dvec3 n =
      glm::transpose(face_from_cube(faces[size_t(k)])) * glm::dvec3(s.x, s.y, -s.z);
  const double len = glm::length(n);
  return len > 0 ? n / len : glm::dvec3(0, 0, -1);
}

size_t HeightfieldFaces::bytes() const {
  size_t b = 0;
  for (const ReliefMap& m : maps) b += m.gpu_bytes();
  return b;
}

HeightfieldFaces bake_heightfield_faces(const TriangleMesh& mesh, const BakeFrame& cube,
                                        int resolution, int count,
                                        const ReverseProjection& projection) {
  if (std::abs(cube.side - cube.height) > 1e-9 * cube.side)
    throw std::invalid_argument("heightfield faces need a cube-shaped frame (cell_frame)");
  HeightfieldFaces hf;
  hf.faces = face_set(count);
  hf.projection = projection;
  for (int face : hf.faces)
    hf.maps.push_back(bake_mesh(mesh, cube, resolution, projection, face_from_cube(face)));
  return hf;
}

}  // namespace rl
