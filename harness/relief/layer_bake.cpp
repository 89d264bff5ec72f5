#include "relief/layer_bake.h"

#include <algorithm>
#include <atomic>
#include <map>
#include <stdexcept>

#include <embree3/rtcore.h>

#include "core/columns.h"
#include "core/embree_util.h"
#include "core/parallel.h"

namespace rl {
namespace {

// A multilayer map's columns (the sweep writes them from the bake's LayerStack).
const ColumnDeclaration layer_columns(
    "relief (multilayer bake)",
    {ColumnSpec{"layers", "", "depth layers per texel of a multilayer map (0: a heightfield)"}
         .neither_better(),
     {"layer_overflow_pct", "% of texels",
      "texels whose ray crossed more surfaces than the map has layers for"},
     {"layer_odd_pct", "% of texels",
      "texels with an odd number of crossings (an open or non-manifold mesh)"},
     ColumnSpec{"depth_complexity", "crossings", "the most surface crossings of one texel's ray"}
         .neither_better(),
     {"normal_storage_err_mean_deg", "degrees",
      "on an 8-bit multilayer map, the layers' normals as Figure 5 stores them (x and y in 8 "
      "bits, z rebuilt on the layer's side) against the normals before: the mean angle over "
      "surface texels"},
     {"normal_storage_err_max_deg", "degrees", "the same, the largest"}});

}  // namespace

namespace {

constexpr int kMaxCrossings = 256;  // bounds the walk along one bake ray
const glm::vec3 kNeutral = kLayeredFloorColor;

struct Crossing {
  double depth;
  glm::vec3 normal;  // outward, tangent frame
  glm::vec3 color;
};

// Per triangle: whether its connected component has a boundary (an edge only one triangle
// uses) -- part of an open surface. Vertices are welded by position, as a mesh file may repeat
// them per face.
std::vector<bool> open_triangles(const TriangleMesh& mesh) {
  const std::vector<uint32_t> id = welded_vertex_ids(mesh);
  std::vector<uint32_t> parent(mesh.triangles.size());
  for (uint32_t t = 0; t < parent.size(); ++t) parent[t] = t;
  auto root = [&](uint32_t t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
  };
  std::map<std::pair<uint32_t, uint32_t>, std::pair<uint32_t, int>> edges;  // first user, uses
  for (uint32_t t = 0; t < mesh.triangles.size(); ++t)
    for (int e = 0; e < 3; ++e) {
      uint32_t a = id[mesh.triangles[t][e]], b = id[mesh.triangles[t][(e + 1) % 3]];
      if (a == b) continue;  // an edge collapsed by the weld, as mesh_closure() skips them
      auto [it, fresh] = edges.try_emplace({std::min(a, b), std::max(a, b)}, t, 0);
      ++it->second.second;
      if (!fresh) parent[root(t)] = root(it->second.first);
    }
  std::vector<bool> open_root(mesh.triangles.size(), false);
  for (const auto& [edge, use] : edges)
    if (use.second == 1) open_root[root(use.first)] = true;
  std::vector<bool> open(mesh.triangles.size());
  for (uint32_t t = 0; t < open.size(); ++t) open[t] = open_root[root(t)];
  return open;
}

}  // namespace

BakeFrame pattern_frame() {
  BakeFrame f;
  f.up = 2;
  f.axis_u = 0;
  f.axis_v = 1;
  f.origin = glm::dvec3(0);
  f.side = 1;
  f.height = 1;
  return f;
}

namespace {

// One texel's bake ray straight down through the mesh: its crossings, top to bottom.
struct CrossingWalk {
  RTCScene scene;
  const TriangleMesh& mesh;
  const BakeFrame& frame;
  glm::dvec3 world_scale;
  const std::vector<bool>& open;  // per triangle: part of an open surface
  double open_gap;

  // The crossings of the ray through texture point a0 (depth just above 0) into `found`;
  // returns how many entered where the order says they leave, or the other way round.
  long walk(const glm::dvec3& a0, std::vector<Crossing>& found) const {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    const glm::dvec3 o = frame.mesh_from_texture(a0);
    const glm::dvec3 d = frame.mesh_from_texture(a0 + glm::dvec3(0, 0, 1)) - o;
    found.clear();
    long misoriented = 0;
    double t0 = 0;
    bool last_entering = false;
    while (found.size() < size_t(kMaxCrossings)) {
      RTCRayHit rh = embree_ray(o, d, t0, 1.0 + 2e-6);
      rtcIntersect1(scene, &ctx, &rh);
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
      const double t = rh.ray.tfar, depth = a0.z + t;  // t counts depth units
      t0 = t + 1e-7;
      const glm::dvec3 ng(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
      const bool entering = glm::dot(ng, d) < 0;
      // A ray through a shared edge may report both triangles at one depth: one crossing.
      if (!found.empty() && depth - found.back().depth < 1e-6 && entering == last_entering)
        continue;
      last_entering = entering;
      const glm::dvec3 nt = frame.texture_normal(ng);  // (u, v, depth) space
      glm::dvec3 n = glm::normalize(
          glm::dvec3(nt.x / world_scale.x, nt.y / world_scale.y, -nt.z / world_scale.z));
      // Outward by the crossing order: up where the ray enters (even), down where it leaves.
      const bool even = found.size() % 2 == 0;
      if (entering != even) ++misoriented;
      if ((even && n.z < 0) || (!even && n.z > 0)) n = -n;
      const glm::vec3 color =
          mesh.triangle_colors.empty() ? kNeutral : mesh.triangle_colors[rh.hit.primID];
      found.push_back({depth, glm::vec3(n), color});
      // An open surface as two layers (Policarpo & Oliveira 2006, Section 7): it is entered
      // and left at once, `open_gap` deeper, facing down there.
      if (open[rh.hit.primID]) {
        found.push_back({depth + open_gap, glm::vec3(-n), color});
        last_entering = !entering;
      }
    }
    return misoriented;
  }
};

}  // namespace

ReliefMap bake_layers(const TriangleMesh& mesh, const BakeFrame& frame, int width, int height,
                      int layers, const glm::dvec3& world_scale, bool close_open,
                      std::optional<double> open_surface_gap) {
  if (layers < 1 || layers > LayerStack::kMaxLayers)
    throw std::invalid_argument("bake_layers: 1 to 8 layers");
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene scene = embree_triangle_scene(device, mesh);
  const size_t texels = size_t(width) * height;
  const std::vector<bool> open =
      open_surface_gap ? open_triangles(mesh) : std::vector<bool>(mesh.triangles.size(), false);
  const CrossingWalk walk{scene, mesh, frame, world_scale, open, open_surface_gap.value_or(0.0)};

  ReliefMap map;
  map.name = mesh.name;
  map.width = width;
  map.height = height;
  map.relief.assign(texels, glm::vec4(0.5f, 0.5f, 1.0f, 1.0f));
  map.color.assign(texels, glm::vec4(kNeutral, 1.0f));
  LayerStack& stack = map.layers;
  stack.count = layers;
  stack.depth.assign(texels * layers, 1.0f);
  stack.normal.assign(texels * layers, glm::vec3(0, 0, 1));
  stack.color.assign(texels * layers, kNeutral);
  std::atomic<long> overflow{0};
  std::atomic<int> max_crossings{0};
  std::atomic<long> misoriented{0};
  std::atomic<long> odd{0};

  parallel_for(texels, [&](size_t begin, size_t end) {
    std::vector<Crossing> found;
    for (size_t i = begin; i < end; ++i) {
      misoriented +=
          walk.walk({(i % width + 0.5) / width, (i / width + 0.5) / height, -1e-6}, found);
      if (found.size() % 2) {
        ++odd;
        if (close_open) found.pop_back();
      }
      const int crossings = int(found.size());
      if (crossings > layers) ++overflow;
      int seen = max_crossings.load();
      while (crossings > seen && !max_crossings.compare_exchange_weak(seen, crossings)) {
      }
      for (int l = 0; l < std::min(crossings, layers); ++l) {
        const size_t k = size_t(l) * texels + i;
        stack.depth[k] = float(std::clamp(found[l].depth, 0.0, 1.0));
        stack.normal[k] = found[l].normal;
        stack.color[k] = found[l].color;
      }
      if (crossings > 0) {
        map.relief[i] = glm::vec4(found[0].normal * 0.5f + 0.5f, stack.depth[i]);
        map.color[i] = glm::vec4(found[0].color, 1.0f);
      }
    }
  });
  stack.overflow_texels = overflow.load();
  stack.max_crossings = max_crossings.load();
  stack.misoriented_crossings = misoriented.load();
  stack.odd_texels = odd.load();
  rtcReleaseScene(scene);
  rtcReleaseDevice(device);
  return map;
}

}  // namespace rl
