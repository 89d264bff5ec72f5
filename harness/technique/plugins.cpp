#include "technique/plugins.h"

#include <dlfcn.h>
#include <elf.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/code_digest.h"
#include "core/error.h"
#include "technique/elf_check.h"
#include "technique/technique.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

bool is_shared_object(const fs::path& p) {
  return p.extension() == ".so" || p.filename().string().find(".so.") != std::string::npos;
}

// The shared objects a path names, in the order they load.
std::vector<fs::path> plugin_files(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw ConfigError("plugin path " + path + ": no such file or folder");
  if (!fs::is_directory(path, ec)) {
    if (!fs::is_regular_file(path, ec))
      throw ConfigError("plugin path " + path + ": not a regular file or a folder");
    return {fs::path(path)};
  }
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(path, ec))
    if (e.is_regular_file() && is_shared_object(e.path())) files.push_back(e.path());
  if (ec) throw ConfigError("plugin folder " + path + ": " + ec.message());
  std::sort(files.begin(), files.end());
  return files;
}

LoadedPlugin load_one(const fs::path& file) {
  const std::string path = fs::canonical(file).string();
  TechniqueRegistry& registry = TechniqueRegistry::instance();
  const std::vector<std::string> before = registry.names();
  std::string refused;
  check_elf_is_whole(path);
  set_registration_error_sink(&refused);
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  set_registration_error_sink(nullptr);
  if (!handle) {
    const char* why = dlerror();
    throw ConfigError("plugin " + path + ": cannot load: " + (why ? why : "unknown error"));
  }
  LoadedPlugin loaded{path, {}};
  // Its code is its bytes: a precompute cached by its code (core/precompute_cache.h) and its
  // rows' technique_code name them.
  const std::string digest = file_digest(path);
  for (const std::string& name : registry.names())
    if (!std::binary_search(before.begin(), before.end(), name)) {
      registry.set_plugin(name, path);
      loaded.techniques.push_back(name);
      register_folder_digest(source_folder(registry.find(name)->source), digest);
    }
  if (!refused.empty()) {
    // The shared object stays loaded (its code may be referenced by what it did register),
    // but none of its techniques may be used: a half-registered plugin is refused whole.
    for (const std::string& name : loaded.techniques) registry.remove(name);
    throw ConfigError("plugin " + path + ": " + refused);
  }
  if (loaded.techniques.empty())
    throw ConfigError("plugin " + path +
                      ": registered no technique (is RL_REGISTER_TECHNIQUE in it, and does it "
                      "link ReliefLab's shared libraries rather than a copy of them?)");
  return loaded;
}

}  // namespace

std::vector<LoadedPlugin> load_plugins(const std::vector<std::string>& paths) {
  static std::set<std::string> loaded_paths;
  std::vector<LoadedPlugin> out;
  for (const std::string& p : paths)
    for (const fs::path& file : plugin_files(p)) {
      if (!loaded_paths.insert(fs::canonical(file).string()).second) continue;
      out.push_back(load_one(file));
    }
  return out;
}

std::vector<std::string> plugin_paths_from_environment() {
  std::vector<std::string> out;
  const char* env = std::getenv("RELIEFLAB_PLUGIN_PATH");
  if (!env) return out;
  std::stringstream ss(env);
  for (std::string part; std::getline(ss, part, ':');)
    if (!part.empty()) out.push_back(part);
  return out;
}

}  // namespace rl
