#pragma once
// The truth a scene asks for: its map's bilinear heightfield, or the mesh it was baked from.
#include <memory>

#include "relief/relief_map.h"
#include "scene/scene.h"
#include "truth/truth_surface.h"

namespace rl {

std::unique_ptr<TruthSurface> make_truth(const SceneDesc& scene, const ReliefMap& map,
                                         double tolerance);

}  // namespace rl
