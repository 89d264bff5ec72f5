#pragma once
// The file-reading half of a scene's config: after parse_scene() (pure), the facts that come
// from its files. Image headers give the relief's native size (any aspect); a baked mesh gives
// the relief depth (its proportions); a base mesh must have uvs; every file's content hash
// enters the scene's canonical description, so a changed file re-measures its cells. Full
// decoding of every asset happens once more before the first cell (run/asset_check.h).
#include "config/config_scene.h"

namespace rl {

// Throws ConfigError naming the config line (the recorded site) and the file.
void read_scene_files(ParsedScene& parsed);

}  // namespace rl
