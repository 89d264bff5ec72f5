#include "config/config_cube.h"

namespace rl {

void apply_in_cube_scene(const toml::table& t, const Src& src, const toml::node& node,
                         SceneDesc& s) {
  if (!s.in_cube()) return;
  const std::string no = "scene '" + s.name + "': " +
                         (s.cell_complex() ? "a cell-complex relief " : "a heightfield object ");
  for (const char* key : {"base", "proxy", "floor", "framing", "truth_resolution", "meta_relief",
                          "ambient_occlusion"})
    if (auto* n = t.get(key))
      fail(src.at(*n), no + "is drawn in its bounding cube; '" + key + "' does not apply");
  const toml::node& truth_site = t.get("truth") ? *t.get("truth") : node;
  if (s.cell_complex() && s.truth != TruthLevel::Mesh && s.truth != TruthLevel::Cells)
    fail(src.at(truth_site),
         no + "is measured against its mesh (truth = \"mesh\") or the surface its distance maps "
              "encode (truth = \"cells\")");
  if (s.heightfield_object() && s.truth != TruthLevel::Mesh)
    fail(src.at(truth_site), no + "is measured against its mesh (truth = \"mesh\")");
  s.proxy = Proxy::Box;
  s.empty_floor = true;
  s.framing = Framing::Fit;
}

}  // namespace rl
