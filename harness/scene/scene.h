#pragma once
// A scene: the relief asset, the base surface it is mapped on (the planar quad, or a curved
// base mesh: harness/scene/base_mesh.h), its scale, the light, the effects it asks for and any
// plain triangle-mesh objects standing in it.
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/effects.h"
#include "relief/relief_map.h"
#include "relief/reverse_projection.h"

namespace rl {
struct ReliefMap;
}

namespace rl {

struct View {
  double elevation_deg = 45;  // 90 = looking straight down on the base
  double azimuth_deg = 0;     // 0 = camera on the +u side, looking along -u
  // The camera turned about its view direction, counter-clockwise seen from the eye: 0 keeps
  // the base's up (its normal) up in the image. Set only where a view is carried into another
  // frame (a three-view impostor's bakes), so the image stays the same world's.
  double roll_deg = 0;
};

// A three-view impostor (ReliefSourceDesc::three_views): of the mesh's axes, the one a view
// looks along most nearly (ties go to `up`, then to the lower axis), and the same view direction
// in the frame of the bake along that axis. A bake along axis a maps mesh axes
// (a + 1, a + 2, a) mod 3 to the quad's (u, v, up), so its views are those of any other bake
// turned about the object's centre.
struct AxisView {
  int up = 1;  // 0, 1, 2 = x, y, z
  View view;
};
AxisView nearest_bake_view(const View& view, int up);
// A point of the world of the bake along `from_up` (its quad's frame, relief depth from_depth)
// where it lies in the world of the bake along `to_up`: turned about the object's centre, as
// the three bakes of one object share a scale.
glm::dvec3 carry_to_bake(const glm::dvec3& point, int from_up, double from_depth, int to_up,
                         double to_depth);

// A view's direction from the target toward the eye, and the camera's up (roll included), in
// the frame of the base's quad (x along u, y along v, z up).
glm::dvec3 view_direction(const View& view);
glm::dvec3 camera_up(const View& view);

// A relief map's size in texels. Maps need not be square: a texture resolution in a sweep
// (texture_res) names the longer side and the shorter one keeps the native aspect.
struct MapSize {
  int width = 256, height = 256;
  int longer() const { return width > height ? width : height; }
  bool operator==(const MapSize& o) const { return width == o.width && height == o.height; }
};

struct ReliefSourceDesc {
  // Exactly one of: a procedural kind, or image files.
  std::string procedural;                 // "sines", "bricks", ...
  std::map<std::string, double> options;  // procedural options
  std::string normal_path, depth_path, color_path;
  bool height_convention = true;  // image stores height (1 = top)
  bool flip_green = false;
  bool normalize = false;  // remap image depths to [0, 1]
  // A value marking texels without data (a GeoTIFF's nodata): left out of the depth range and
  // filled at the deepest valid depth. NaN: none given.
  double nodata = std::numeric_limits<double>::quiet_NaN();
  std::string mesh_path;      // a mesh baked into the map (Baboud & Decoret)
  size_t mesh_triangles = 0;  // its triangles as read with the config, for the memory estimate
  int mesh_up = 1;            // its up axis: 0, 1, 2 = x, y, z
  double reverse_cop = 0;     // reverse perspective: centre of projection depth (> 1), or 0
  // > 0: the mesh is an object from that many heightfields (1, 2, 3 or 6 faces of its bounding
  // cube: relief/heightfield_faces.h), each with reverse_cop; 0: one bake from the top of its
  // footprint box.
  int faces = 0;
  int layers = 0;  // > 0: baked into that many depth layers (a mesh or a pattern)
  // A relief impostor baked along all three axes, the bake whose axis is nearest the view drawn
  // (Policarpo & Oliveira 2006, Section 4's remedy for a quad seen edge-on).
  bool three_views = false;
  // A mesh's open surfaces baked as two layers this far apart in depth (relief/layer_bake.h);
  // without it, a texel whose ray crosses an odd number of times drops its deepest crossing.
  std::optional<double> open_surface_gap;
  // The mesh encoded as a cubic cell complex instead of baked into a map (Apaza & Andujar,
  // relief/cell_complex.h): `native` is each domain face's map size.
  struct Cells {
    bool active = false;
    int grid = 0;             // N; 0 = chosen by the occluded-fragment ratio (Section 3.3.3)
    double threshold = 0.05;  // ... below this ratio
    int grid_max = 16;        // ... or at most this N
    int distance_bits = 16;   // 16 (Table 1) or 8
    int subdivide = 0;        // midpoint-subdivide the mesh this many times first (x4 each)
    // The distance and normal maps drawn on the GPU (Section 3.3.2, gpu/cell_gpu_sampling.h)
    // instead of the CPU's per-texel projection lines; the rest of the complex is the CPU's.
    bool gpu_sampling = false;
  } cells;
  MapSize native;  // size when texture_res = 0 ("native")
  // A non-height-field pattern generated as a mesh (relief/pattern_mesh.h): weave, helix.
  bool pattern_mesh() const;
  // The map's size at a sweep's texture_res (the longer side; 0 = native).
  MapSize size_at(int texture_res) const;
  // World length of the map along v over its length along u: a planar quad keeps its texels
  // square, so a 512 x 128 map lies on a 4:1 rectangle.
  double aspect() const { return double(native.height) / native.width; }
};

struct Material {
  glm::dvec3 ambient{0.12, 0.12, 0.12};
  glm::dvec3 diffuse{1.0, 1.0, 1.0};
  glm::dvec3 specular{0.25, 0.25, 0.25};
  double shininess = 32;
  double shadow_intensity = 0.4;  // colour factor in shadow (Listing 5.3)
};

// What the rasteriser draws for a relief: the base surface itself (rays enter at the top),
// or the relief volume's bounding box (Baboud & Decoret, Section 3): rays also enter through
// the sides, misses are discarded, and the silhouette comes from the search.
enum class Proxy { Base, Box };

// What the truth traces: the relief as the technique samples it (the bilinear heightfield of
// the map), or, for a baked mesh, the mesh itself (includes representation error).
// A multilayer map adds the truth of its own layers (nearest sampled), so search error and
// representation error split there too; a cell complex the surface its distance maps encode.
enum class TruthLevel { Sampled, Mesh, Layers, Cells };
// "sampled", "mesh", "layers", "cells": the config's and the rows' name of a level.
const char* truth_level_name(TruthLevel level);

// The surface the relief is mapped onto. "plane" is the planar quad of PlanarBase (the
// heightfield truth); every other kind is a base mesh displaced along its normals (chapter 5):
// generated "cube", "sphere", "torus", the Utah "teapot", or a mesh file with uvs.
struct BaseDesc {
  std::string kind = "plane";  // plane, cube, sphere, torus, teapot, or "file"
  std::string path;            // kind == "file": an OBJ/PLY with texture coordinates
  int segments = 32;           // generated sphere/torus: quads around the main circle
  bool curved() const { return kind != "plane"; }
};

// A plain triangle-mesh object in the scene (not relief mapped): chapter 5's Figure 5.20
// interpenetration. Drawn with a standard shader before the relief and traced by the truth.
struct SceneObject {
  std::string shape = "sphere";  // "sphere", "cube", or a mesh file path
  glm::dvec3 center{0};
  double radius = 0.25;  // half the side for a cube; a mesh is fitted into this sphere
  glm::dvec3 albedo{0.85, 0.35, 0.2};
};

// The shadow map of scene_shadows (core/effects.h): rendered from the light, a perspective view
// that holds the scene's bounds (the relief's slab and its objects), looked up per shaded point
// at its nearest texel (no filtering, as the papers' shadow maps).
struct ShadowMapDesc {
  int size = 1024;  // texels on a side
  // The relief drawn into it at the depth of its found hit (chapter 5, "Depth Correct"), or at
  // its base's (what a shadow map of the undisplaced surface would hold).
  bool corrected_depth = true;
  // How far beyond the map's surface a point must lie to be in shadow: `bias` world units plus
  // `slope_bias` times the surface's fall across one texel (harness/glsl/shadow_map.glsl).
  double bias = 0.002;
  double slope_bias = 1.0;
};

// How the camera frames a planar scene. Fit: the whole quad's bounding sphere in view (a
// grazing view then sees a thin sliver). Fill: the relief fills the viewport at every view:
// the quad is made long enough (more tiles) and the camera's field of view narrows with the
// elevation (at most elevation / 2), so a row still means one view angle (the spread is in
// the row as elev_min_deg / elev_max_deg).
enum class Framing { Fit, Fill };

// Options of the ambient_occlusion effect (Limberger et al., Section IV).
struct AmbientOcclusionDesc {
  int directions = 50;  // horizon directions of the texture-space AO map (7.2 degrees apart)
  bool filter = true;   // the paper's low-pass filter over occluded texels
  // World depth the AO map was computed for; 0 = the scene's depth. Where it differs, the
  // scene's depth is a rescale s = depth / map_depth of the relief the map was made for.
  double map_depth = 0;
  // How a rescaled relief's AO is obtained from that map: Eq. 6 in the shader, or not at all
  // (the stale map, the baseline Eq. 6 improves on).
  enum class Update { Eq6, None } update = Update::Eq6;
  // Truth (truth/reference_ao.h): `samples` cosine-weighted hemisphere rays per pixel,
  // stratified; the standard error is reported (ao_ref_stderr). 144 stratified rays state a
  // lower noise floor on the default sweep's AO scenes than 256 rays did with the binomial error
  // (bench_truth BM_ReferenceAo). stderr_target > 0 stops at a 6 x 6 (or coarser) grid where the
  // error already meets it: fewer rays, but the stop favours pixels whose few rays all agree,
  // which biases mostly open pixels toward open (the reference was up to 0.005 brighter on the
  // AO rescale study's shallow maps at 0.02, for 13% fewer rays on the rock wall), so it is off.
  int samples = 144;
  double stderr_target = 0;
  // false: the technique draws no AO (none compiled, no map built) while the truth keeps its
  // reference AO -- the scene without AO beside the same scene with it (Limberger et al.,
  // Figure 7), both scored against the one AO truth.
  bool render = true;
  // Who computes the AO map: the line sweep on the CPU (relief/horizon_sweep.h: 1.1-2 s at
  // 1024^2 on 2 cores), the paper's per-texel march on the CPU (relief/ao_map.h: what the sweep
  // approximates, tens of seconds at 1024^2), or that march in a fragment shader
  // (gpu/gpu_ao_map.h: the GPU's way; on llvmpipe slower than the CPU's march).
  enum class MapMethod { LineSweep, March, FragmentShader } map_method = MapMethod::LineSweep;
  // The depth the AO map is computed for, and the scene's depth over it.
  double depth_of_map(double depth) const { return map_depth > 0 ? map_depth : depth; }
  double rescale(double depth) const { return depth / depth_of_map(depth); }
};

// A meta-relief (Limberger, Schetinger & Oliveira, Section III; relief/meta_relief.h): finer
// relief layers added on top of the scene's relief (layer 0), each with its own source,
// resolution, tiling and weights.
struct MetaLayerDesc {
  ReliefSourceDesc relief;
  double tiling = 1;  // repeats per unit of the base's texture coordinate (fractional allowed)
  double weight_normal = 1, weight_depth = 1;  // w_n, w_d of Eqs. 1-2
};

// Layers of a meta-relief, the scene's relief included: the shaders bind one texture unit each
// (units 10 to 17).
inline constexpr int kMaxMetaLayers = 8;

struct MetaReliefDesc {
  std::vector<MetaLayerDesc> layers;           // the finer layers (layer 0 is scene.relief)
  double weight_normal = 1, weight_depth = 1;  // layer 0's w_n, w_d
  // Runtime: the shader samples every layer per fetch (techniques with meta_relief support).
  // Baked: one map of the combination at bake_resolution, for every heightfield technique.
  enum class Combine { Runtime, Baked } combine = Combine::Runtime;
  int bake_resolution = 0;  // longer side of the bake; 0 = layer 0's size
  // Longer side at which layer 0's colour map is read for the bake's colour (0 = layer 0's
  // size): high-resolution colour over low-resolution geometry (Figure 14, column d). The
  // colour texture is the bake's, so it needs bake_resolution as high.
  int color_resolution = 0;
  // The AO map of the combination: the layers' maps multiplied or their minimum (Section IV-A),
  // or computed on the bake itself.
  enum class AoCombine { Product, Min, Bake } ao_combine = AoCombine::Product;
  bool active() const { return !layers.empty(); }
  bool runtime() const { return active() && combine == Combine::Runtime; }  // combined per fetch
};

struct SceneDesc {
  std::string name;
  Framing framing = Framing::Fit;
  double fill_footprint = 1.0;  // Fill: world width the viewport spans at the target
  BaseDesc base;
  std::vector<SceneObject> objects;
  Proxy proxy = Proxy::Base;
  TruthLevel truth = TruthLevel::Sampled;
  // The texture resolution (longer side) the truth's map is built at, whatever the cell's;
  // 0 = the cell's. Measures a low-resolution map against the surface a finer one stands for
  // (Limberger et al., Figure 14).
  int truth_texture_res = 0;
  // The colour map's resolution (longer side) whatever the cell's texture resolution; 0 = the
  // relief's. Baboud & Decoret, Section 4.3: a larger colour map over a smaller depth map, the
  // search reading only depths. Heightfields from images or procedures only.
  int color_texture_res = 0;
  // The truth's colour map at this resolution (longer side), whatever the technique's; 0 = the
  // technique's (color_texture_res, else the cell's). One reference colour for scenes that
  // differ only in their colour map's resolution, so that their rows are judged alike.
  int truth_color_texture_res = 0;
  // With a box proxy, is depth 1 (the box's bottom) a floor, or empty (an object baked from a
  // mesh: chapter 5's "alpha = d < 1", Baboud & Decoret's objects)? Rays reaching it hit the
  // floor, or leave the box.
  bool empty_floor = false;
  // A layered relief's solid floor: its colour (Policarpo & Oliveira 2006, Figure 9 right:
  // where rays miss the pattern, the underlying model in its own colour).
  glm::vec3 floor_color = kLayeredFloorColor;
  ReverseProjection projection;  // a baked mesh's reverse perspective (Section 4), or none
  // Draw the frustum cut to the relief's bounding box (Baboud & Decoret, Section 4.1).
  bool clip_frustum = false;
  ReliefSourceDesc relief;
  double size = 1.0;     // world side of the quad
  double tile = 1.0;     // texture repeats across the quad
  double depth = 0.08;   // world depth of the relief (depth 1 in the map)
  bool quantize = true;  // 8-bit textures like the papers; false keeps float
  EffectSet effects;
  AmbientOcclusionDesc ao;   // used when effects has AmbientOcclusion
  ShadowMapDesc shadow_map;  // used when effects has SceneShadows
  // The effects a technique is asked to simulate: `effects`, less AO where ao.render is false
  // (the truth simulates `effects` whole).
  EffectSet drawn_effects() const {
    EffectSet drawn = effects;
    if (!ao.render) drawn.remove(Effect::AmbientOcclusion);
    return drawn;
  }
  MetaReliefDesc meta;  // finer relief layers on top of `relief`, if any
  glm::dvec3 light_position{0.9, -0.6, 1.4};
  Material material;
  double fov_deg = 40;
  double distance = 0;        // camera distance to the quad centre; 0 = fit the quad in view
  double shadow_bias = 0.02;  // depth units (Listing 5.3's shadow_threshold)
  // A relief impostor (Policarpo & Oliveira 2006, Section 4): a mesh baked into depth layers,
  // drawn on one quad through its middle (depth 0.5) and seen from either side.
  bool impostor() const { return relief.layers > 0 && !relief.mesh_path.empty() && !base.curved(); }
  // Set on the bakes of a three-view impostor along its other two axes: the name of the
  // [[scene]] whose views nearest this bake's axis it draws (their rows carry that name).
  std::string bake_of;
  // A closed mesh as a cubic cell complex (relief = { cells = "mesh.obj" }): drawn by the
  // techniques that read it, in its bounding cube (the box proxy, depth = size).
  bool cell_complex() const { return relief.cells.active; }
  // A mesh as an object from several heightfields (relief = { mesh = ..., faces = N }): drawn
  // by the techniques that read them, in its bounding cube like a cell complex.
  bool heightfield_object() const { return relief.faces > 0; }
  // A closed object in its bounding cube (box proxy, depth = size, empty floor), seen from
  // any side.
  bool in_cube() const { return cell_complex() || heightfield_object(); }
};

// Position errors of a cell complex are in 1/256 of its cube's side (what a 64^2 face map on a
// 4^3 grid resolves), whatever its grid and face resolution: one yardstick across a grid study.
inline constexpr int kCellMetricTexels = 256;

// The planar base: texture space (u, v, depth) <-> world. The quad spans [-size/2, size/2] in
// x (u) and `aspect` times that in y (v) at z = 0; depth 1 lies `depth` below it.
struct PlanarBase {
  double size = 1, tile = 1, depth = 0.08;
  double aspect = 1;  // world length along v / along u (the map's height / width)

  double size_v() const { return size * aspect; }
  glm::dvec3 dpdu() const { return {size / tile, 0, 0}; }
  glm::dvec3 dpdv() const { return {0, size_v() / tile, 0}; }
  glm::dvec3 normal() const { return {0, 0, 1}; }
  glm::dvec3 world_from_texture(const glm::dvec3& uvd) const {
    return {-0.5 * size + uvd.x * size / tile, -0.5 * size_v() + uvd.y * size_v() / tile,
            -uvd.z * depth};
  }
  glm::dvec3 texture_from_world(const glm::dvec3& p) const {
    return {(p.x + 0.5 * size) * tile / size, (p.y + 0.5 * size_v()) * tile / size_v(),
            -p.z / depth};
  }
  glm::dvec3 texture_direction(const glm::dvec3& d) const {
    return {d.x * tile / size, d.y * tile / size_v(), -d.z / depth};
  }
  // World side of a texel of a map `width` texels across u (texels are square).
  double texel_world(int width) const { return size / tile / width; }
};

PlanarBase planar_base(const SceneDesc& scene);

// Vertices of the base surface as the shaders receive them.
struct BaseVertex {
  glm::vec3 position;
  glm::vec2 uv;
  glm::vec3 dpdu;  // world change per unit u (tangent scaled by the mapping)
  glm::vec3 dpdv;
  glm::vec3 normal;
  float entry_depth;          // depth at which a ray entering here starts (0 on the base / box top)
  glm::vec2 curvature{0.0f};  // quadric (A, B) of the base along dpdu, dpdv (chapter 5)
};

struct BaseGeometry {
  std::vector<BaseVertex> vertices;
  std::vector<unsigned> indices;
};

// The base quad, or for Proxy::Box the closed box [0, tile]^2 x [0, 1] in texture space with
// outward faces (counter-clockwise seen from outside), or a curved base's mesh. With
// clip_frustum, `map` gives the relief the frustum is cut to (scene/clipped_frustum.h).
BaseGeometry make_base_geometry(const SceneDesc& scene, const ReliefMap* map = nullptr);

// Radius of a sphere around the origin holding the base and its relief (camera fitting).
double scene_radius(const SceneDesc& scene);

struct Camera {
  glm::dvec3 eye, target, up;
  double fov_y_deg = 40;
  double near_plane = 0.01, far_plane = 100;
  int width = 256, height = 256;

  glm::dmat4 view_matrix() const;
  glm::dmat4 projection_matrix() const;
  // World ray through the centre of pixel (x, y), y = 0 the bottom row (GL's convention).
  void pixel_ray(int x, int y, glm::dvec3& origin, glm::dvec3& direction) const;
};

Camera make_camera(const SceneDesc& scene, const View& view, int width, int height);

// The light's view of scene_shadows' shadow map: from the light toward the centre of the sphere
// that holds the relief's slab and the scene's objects, its field of view just holding that
// sphere, near and far planes tight about it; shadow_map.size texels square. Throws
// std::runtime_error naming the scene when the light lies within the sphere or, on the planar
// base, not above it (no perspective view from there holds the scene).
Camera light_camera(const SceneDesc& scene);

// Fill framing: the vertical field of view at an elevation, and how many times the scene's
// footprint the quad must span so that every ray of views down to `min_elevation_deg` (at
// viewport aspects up to `max_aspect`) meets it.
double fill_fov_deg(const SceneDesc& scene, double elevation_deg);
int fill_quad_factor(const SceneDesc& scene, double min_elevation_deg, double max_aspect);
// Makes `scene` a fill-framed one: its quad (of side fill_footprint = the current size) is
// lengthened by whole tiles for those views; the texel size stays.
void apply_fill_framing(SceneDesc& scene, double min_elevation_deg, double max_aspect);

}  // namespace rl
