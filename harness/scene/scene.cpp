#include "scene/scene.h"

#include "relief/pattern_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/base_mesh.h"
#include "scene/clipped_frustum.h"

namespace rl {

PlanarBase planar_base(const SceneDesc& scene) {
  PlanarBase b;
  b.size = scene.size;
  b.tile = scene.tile;
  b.depth = scene.depth;
  b.aspect = scene.relief.aspect();
  return b;
}

glm::dvec3 view_direction(const View& view) {
  const double el = glm::radians(view.elevation_deg), az = glm::radians(view.azimuth_deg);
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

glm::dvec3 camera_up(const View& view) {
  // d(direction)/d(elevation): perpendicular to the view direction at every elevation, so the
  // top-down view (90 degrees) needs no special case; then turned by the roll.
  const double el = glm::radians(view.elevation_deg), az = glm::radians(view.azimuth_deg);
  const glm::dvec3 up(-std::sin(el) * std::cos(az), -std::sin(el) * std::sin(az), std::cos(el));
  if (view.roll_deg == 0) return up;
  const double roll = glm::radians(view.roll_deg);
  return std::cos(roll) * up + std::sin(roll) * glm::cross(view_direction(view), up);
}

namespace {

// A vector of the quad frame of the bake along `up`, along the mesh's own x, y, z, and back.
glm::dvec3 mesh_from_bake(const glm::dvec3& v, int up) {
  glm::dvec3 m;
  m[(up + 1) % 3] = v.x;
  m[(up + 2) % 3] = v.y;
  m[up] = v.z;
  return m;
}

glm::dvec3 bake_from_mesh(const glm::dvec3& m, int up) {
  return {m[(up + 1) % 3], m[(up + 2) % 3], m[up]};
}

}  // namespace

glm::dvec3 carry_to_bake(const glm::dvec3& point, int from_up, double from_depth, int to_up,
                         double to_depth) {
  // Each bake's world has the object's centre at (0, 0, -depth / 2) and one scale.
  const glm::dvec3 from_centre(0, 0, -0.5 * from_depth), to_centre(0, 0, -0.5 * to_depth);
  return to_centre + bake_from_mesh(mesh_from_bake(point - from_centre, from_up), to_up);
}

AxisView nearest_bake_view(const View& view, int up) {
  const glm::dvec3 mesh = mesh_from_bake(view_direction(view), up);
  AxisView out;
  out.up = up;
  // Within 1e-12 is a tie (45 degrees puts cos and sin an ulp apart): the earlier axis keeps it.
  for (int a = 0; a < 3; ++a)
    if (std::abs(mesh[a]) > std::abs(mesh[out.up]) + 1e-12) out.up = a;
  const glm::dvec3 along = bake_from_mesh(mesh, out.up);
  if (out.up == up) {
    out.view = view;  // the same bake: the view as given, to the bit
    return out;
  }
  // Rounded to 1e-9 degrees: a view on an axis plane keeps a clean zero (cells are keyed on it).
  auto clean = [](double deg) { return std::round(deg * 1e9) / 1e9; };
  out.view.elevation_deg = clean(glm::degrees(std::asin(std::clamp(along.z, -1.0, 1.0))));
  const double az_deg = clean(glm::degrees(std::atan2(along.y, along.x)));
  out.view.azimuth_deg = az_deg < 0 ? az_deg + 360 : az_deg;
  // The camera's up as the given view has it, carried into the bake's frame, against the up
  // the bake's own view would take: the roll that keeps the image the same.
  const glm::dvec3 wanted = bake_from_mesh(mesh_from_bake(camera_up(view), up), out.up);
  const View unrolled{out.view.elevation_deg, out.view.azimuth_deg};
  const glm::dvec3 plain = camera_up(unrolled), side = glm::cross(view_direction(unrolled), plain);
  out.view.roll_deg =
      clean(glm::degrees(std::atan2(glm::dot(wanted, side), glm::dot(wanted, plain))));
  return out;
}

const char* truth_level_name(TruthLevel level) {
  switch (level) {
    case TruthLevel::Mesh:
      return "mesh";
    case TruthLevel::Layers:
      return "layers";
    case TruthLevel::Cells:
      return "cells";
    default:
      return "sampled";
  }
}

bool ReliefSourceDesc::pattern_mesh() const {
  return is_pattern_mesh(procedural);
}

MapSize ReliefSourceDesc::size_at(int texture_res) const {
  if (texture_res <= 0 || texture_res == native.longer()) return native;
  const int shorter = int(
      std::lround(double(texture_res) * std::min(native.width, native.height) / native.longer()));
  const int s = std::max(2, shorter);
  return native.width >= native.height ? MapSize{texture_res, s} : MapSize{s, texture_res};
}

double scene_radius(const SceneDesc& scene) {
  // A curved base is fitted into the sphere of diameter `size`; its relief lies inside.
  if (scene.base.curved()) return 0.5 * scene.size;
  // An object in its cube, seen about its centre.
  if (scene.in_cube()) return std::sqrt(0.75) * scene.size;
  const PlanarBase base = planar_base(scene);
  return std::sqrt(0.25 * base.size * base.size + 0.25 * base.size_v() * base.size_v() +
                   scene.depth * scene.depth);
}

BaseGeometry make_base_geometry(const SceneDesc& scene, const ReliefMap* map) {
  BaseGeometry g;
  if (scene.base.curved()) return base_geometry(make_base_mesh(scene.base, scene.size, scene.tile));
  const PlanarBase base = planar_base(scene);
  auto vertex = [&](const glm::dvec3& uvd) {
    BaseVertex v;
    v.position = glm::vec3(base.world_from_texture(uvd));
    v.uv = glm::vec2(uvd);
    v.dpdu = glm::vec3(base.dpdu());
    v.dpdv = glm::vec3(base.dpdv());
    v.normal = glm::vec3(base.normal());
    v.entry_depth = float(uvd.z);
    return v;
  };
  AffineBox box;
  if (scene.proxy == Proxy::Box && scene.clip_frustum && map &&
      relief_affine_bounds(*map, scene.projection, scene.empty_floor, box)) {
    // Faces in affine coordinates, which interpolate correctly across each (planar) face.
    for (const std::vector<glm::dvec3>& face : clipped_frustum_faces(scene.projection, box)) {
      const unsigned first = unsigned(g.vertices.size());
      for (const glm::dvec3& a : face) g.vertices.push_back(vertex(a));
      for (unsigned k = 1; k + 1 < face.size(); ++k)
        for (unsigned c : {0u, k, k + 1}) g.indices.push_back(first + c);
    }
    return g;
  }
  if (scene.proxy == Proxy::Box) {
    // Corners in texture space (u, v, depth); depth grows downward (world -z).
    const double t = scene.tile;
    // With a reverse projection the box is a frustum in the base's affine space; vertices
    // carry affine coordinates, which interpolate correctly across the (planar) faces.
    auto corner = [&](int i) {
      return scene.projection.affine_from_texture(
          glm::dvec3((i & 1) ? t : 0, (i & 2) ? t : 0, (i & 4) ? 1 : 0));
    };
    // Each face as four corner indices, counter-clockwise seen from outside in world space.
    const int faces[6][4] = {{0, 1, 3, 2},   // top (depth 0, world +z)
                             {4, 6, 7, 5},   // bottom
                             {0, 4, 5, 1},   // v = 0
                             {2, 3, 7, 6},   // v = tile
                             {0, 2, 6, 4},   // u = 0
                             {1, 5, 7, 3}};  // u = tile
    for (const auto& f : faces) {
      const unsigned first = unsigned(g.vertices.size());
      for (int c : f) g.vertices.push_back(vertex(corner(c)));
      for (unsigned k : {0u, 1u, 2u, 0u, 2u, 3u}) g.indices.push_back(first + k);
    }
    return g;
  }
  const glm::vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const double quad_depth = scene.impostor() ? 0.5 : 0.0;  // an impostor's quad: its middle
  for (const glm::vec2& c : corners)
    g.vertices.push_back(vertex({c.x * scene.tile, c.y * scene.tile, quad_depth}));
  g.indices = {0, 1, 2, 0, 2, 3};
  return g;
}

glm::dmat4 Camera::view_matrix() const {
  return glm::lookAt(eye, target, up);
}

glm::dmat4 Camera::projection_matrix() const {
  return glm::perspective(glm::radians(fov_y_deg), double(width) / height, near_plane, far_plane);
}

void Camera::pixel_ray(int x, int y, glm::dvec3& origin, glm::dvec3& direction) const {
  const glm::dvec3 forward = glm::normalize(target - eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, up));
  const glm::dvec3 true_up = glm::cross(right, forward);
  const double tan_half = std::tan(glm::radians(fov_y_deg) * 0.5);
  const double aspect = double(width) / height;
  const double ndc_x = (x + 0.5) / width * 2.0 - 1.0;
  const double ndc_y = (y + 0.5) / height * 2.0 - 1.0;
  origin = eye;
  direction =
      glm::normalize(forward + right * (ndc_x * tan_half * aspect) + true_up * (ndc_y * tan_half));
}

double fill_fov_deg(const SceneDesc& scene, double elevation_deg) {
  return std::min(scene.fov_deg, 0.5 * elevation_deg);
}

namespace {

// Fill framing's camera distance: the narrower side of the viewport spans the footprint at
// the target.
double fill_distance(const SceneDesc& scene, double fov_y_deg, double aspect) {
  double half = glm::radians(fov_y_deg) * 0.5;
  if (aspect < 1) half = std::atan(std::tan(half) * aspect);
  return 0.5 * scene.fill_footprint / std::tan(half);
}

}  // namespace

int fill_quad_factor(const SceneDesc& scene, double min_elevation_deg, double max_aspect) {
  const double el = glm::radians(std::clamp(min_elevation_deg, 0.5, 90.0));
  const double fov = fill_fov_deg(scene, glm::degrees(el));
  const double h = glm::radians(fov) * 0.5;
  const double distance = fill_distance(scene, fov, std::min(1.0, max_aspect));
  const double eye_height = distance * std::sin(el), eye_back = distance * std::cos(el);
  // The top rays' hits, beyond the target, and their sideways reach (wider viewports reach
  // further sideways).
  const double top = std::max(el - h, 1e-3);
  const double far = eye_height / std::tan(top) - eye_back;
  const double side = eye_height / std::sin(top) * std::tan(h) * std::max(1.0, max_aspect);
  const double half = std::max(far, eye_back) + side + scene.fill_footprint;
  return int(std::ceil(2 * half / scene.fill_footprint));
}

void apply_fill_framing(SceneDesc& scene, double min_elevation_deg, double max_aspect) {
  scene.framing = Framing::Fill;
  // The footprint is the quad's shorter side, so the lengthened quad is long enough both ways.
  scene.fill_footprint = scene.size * std::min(1.0, scene.relief.aspect());
  const int factor = fill_quad_factor(scene, min_elevation_deg, max_aspect);
  scene.size *= factor;
  scene.tile *= factor;
}

Camera make_camera(const SceneDesc& scene, const View& view, int width, int height) {
  if (scene.framing == Framing::Fill) {
    Camera cam;
    cam.width = width;
    cam.height = height;
    cam.fov_y_deg = fill_fov_deg(scene, view.elevation_deg);
    const double el = glm::radians(view.elevation_deg);
    const double distance = fill_distance(scene, cam.fov_y_deg, double(width) / height);
    cam.target = glm::dvec3(0);
    cam.eye = view_direction(view) * distance;
    cam.up = camera_up(view);
    // A map of extreme aspect (8192 x 2) frames its short side from closer than 1e-3: the
    // near plane shrinks with the distance there, or it clipped the whole relief away (every
    // technique drew nothing while the ray-traced truth covered the view).
    cam.near_plane =
        std::max(std::min(1e-3, 1e-3 * distance), 0.5 * (distance * std::sin(el) - scene.depth));
    cam.far_plane = 2 * distance + 2 * scene.size;
    return cam;
  }
  Camera cam;
  cam.width = width;
  cam.height = height;
  cam.fov_y_deg = scene.fov_deg;
  // Fit the quad's bounding sphere (relief included) in the narrower field of view.
  const double radius = scene_radius(scene);
  double half_fov = glm::radians(scene.fov_deg) * 0.5;
  if (width < height) half_fov = std::atan(std::tan(half_fov) * width / height);
  const double distance = scene.distance > 0 ? scene.distance : radius / std::sin(half_fov);
  // Aim at the top of the relief: at grazing elevations a target inside the relief would put
  // the eye below the top plane.
  cam.target = glm::dvec3(0, 0, 0);
  if (scene.impostor()) cam.target.z = -0.5 * scene.depth;  // the quad through its middle
  if (scene.in_cube()) cam.target.z = -0.5 * scene.depth;   // the cube's centre
  cam.eye = cam.target + view_direction(view) * distance;
  cam.up = camera_up(view);
  cam.near_plane = std::max(1e-3, distance - 2 * radius) * 0.5;
  cam.far_plane = distance + 4 * radius + 10 * scene.size;
  return cam;
}

Camera light_camera(const SceneDesc& scene) {
  // The bounds: the relief's (about the origin; a planar one's slab below it) and each object's
  // sphere (a cube's corners).
  glm::dvec3 centre(0, 0, scene.base.curved() ? 0.0 : -0.5 * scene.depth);
  double radius = scene_radius(scene);
  for (const SceneObject& o : scene.objects) {
    const double r = o.shape == "cube" ? std::sqrt(3.0) * o.radius : o.radius;
    const double d = glm::length(o.center - centre);
    if (d + r <= radius) continue;
    // The smallest sphere holding both.
    const double grown = 0.5 * (radius + d + r);
    if (d > 0) centre += (o.center - centre) * ((grown - radius) / d);
    radius = grown;
  }
  const double distance = glm::length(scene.light_position - centre);
  const auto fail = [&](const std::string& why) {
    char at[96];
    std::snprintf(at, sizeof at, "(%g, %g, %g)", scene.light_position.x, scene.light_position.y,
                  scene.light_position.z);
    throw std::runtime_error("scene '" + scene.name + "': scene_shadows: the light at " + at + " " +
                             why);
  };
  if (!scene.base.curved() && scene.light_position.z <= 0) fail("is not above the base (z > 0)");
  if (distance <= 1.01 * radius) {
    char bounds[96];
    std::snprintf(bounds, sizeof bounds, "%g of (%g, %g, %g)", radius, centre.x, centre.y,
                  centre.z);
    fail(std::string("lies within the scene's bounds (a sphere of radius ") + bounds +
         "): its shadow map's view cannot hold them; move it further out");
  }
  Camera cam;
  cam.eye = scene.light_position;
  cam.target = centre;
  const glm::dvec3 forward = (centre - cam.eye) / distance;
  cam.up = std::abs(forward.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  cam.fov_y_deg = 2 * glm::degrees(std::asin(radius / distance));
  cam.near_plane = std::max(distance - radius, 1e-3 * distance);
  cam.far_plane = distance + radius;
  cam.width = cam.height = scene.shadow_map.size;
  return cam;
}

}  // namespace rl
