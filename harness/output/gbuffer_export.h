#pragma once
// Raw G-buffers as multi-channel OpenEXR files (`gbuffers = true` in [sweep]): one per cell
// and one per truth, 32-bit float, zip-compressed, the file's first row the top of the
// picture. Channels (uncovered pixels hold 0 in every channel; A is the mask):
//
//   R, G, B        shaded colour, linear
//   A              coverage: 1 where the relief (or an object) was hit
//   P.X, P.Y, P.Z  world-space hit position
//   N.X, N.Y, N.Z  world-space shading normal
//   uv.U, uv.V     texture coordinate of the hit (tiled: may exceed 1)
//   Z              camera-space depth of the hit: distance along the view axis
//   relief_depth   relief depth of the hit, 0 (top) to 1 (bottom); planar bases only
//   truth_bound    how far the truth's hit may be off, a world distance along the ray
//                  (truth/truth_render.h truth_hit_bound; 0 for a technique)
//   layer          layer of a multilayer map (0 for heightfields)
//   fetches        texture fetches this pixel's search made (0 in a truth)
//   shadow         1 where the hit is in shadow (scenes with self_shadow)
//   ao, ao_stderr  ambient visibility shaded with and its standard error (the truth's hemisphere
//                  sampling; 0 for a technique); scenes with ambient_occlusion only, last
//
// Header: the camera as OpenEXR's standard worldToCamera (view) and worldToScreen
// (projection x view) matrices and as relieflab:view, relieflab:projection; the GL viewport as
// relieflab:viewport (Box2i, (0, 0) to (width - 1, height - 1)); relieflab:eye, fov_y_deg,
// near, far; and relieflab:scene, technique, params, key. Matrices are stored in OpenGL's
// column-major order, which is Imath's row-vector convention: p_camera = p_world * M.
#include <string>

#include "core/gbuffer.h"
#include "scene/scene.h"

namespace rl {

struct GBufferLabels {
  std::string scene, technique, params, key;  // technique/params empty for a truth
};

// Writes through a temporary file renamed into place (an interrupted run leaves no partial
// file). Throws std::runtime_error naming the file on failure.
void write_gbuffer_exr(const std::string& path, const GBuffer& g, const SceneDesc& scene,
                       const Camera& camera, const GBufferLabels& labels);

}  // namespace rl
