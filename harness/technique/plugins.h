#pragma once
// Techniques built outside the tree: shared objects compiled against the installed package
// (find_package(ReliefLab); examples/plugin/ is one), each registering its techniques with
// RL_REGISTER_TECHNIQUE and its GLSL with the registrar relieflab_add_plugin() generates, when
// it is loaded. The CLI loads the folders named by --plugins and by $RELIEFLAB_PLUGIN_PATH
// before it reads a config, so a sweep, `list` and the docs see a plugin's techniques as they
// see the built-in ones.
#include <string>
#include <vector>

namespace rl {

struct LoadedPlugin {
  std::string path;                     // the shared object, canonical
  std::vector<std::string> techniques;  // the techniques it registered
};

// Loads each path: a shared object (*.so), or a folder whose *.so files are loaded in name
// order. Throws ConfigError naming the file: not found, not loadable (the loader's message),
// a registration refused (a technique name taken, inconsistent metadata) or no technique
// registered at all. A path already loaded is skipped.
std::vector<LoadedPlugin> load_plugins(const std::vector<std::string>& paths);

// The folders listed in $RELIEFLAB_PLUGIN_PATH (separated by ':'), empty ones dropped.
std::vector<std::string> plugin_paths_from_environment();

}  // namespace rl
