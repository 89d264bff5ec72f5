#include "relief/image_backend.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/data_paths.h"

namespace rl {
namespace {

constexpr const char* kEntry = "relieflab_image_backend";

struct LoadedBackend {
  const ImageBackend* backend = nullptr;
  std::string description;
};

// Where a module named `file` may be: beside the libraries (the build folder, or <prefix>/lib
// installed or relocated), else, where the libraries' own folder cannot be found, beside the
// running program. Never a path the build wrote in: a package moved to another machine must not
// load whatever lies at its build folder's path there (another user's code, under /tmp).
std::vector<std::string> module_candidates(const std::string& file) {
  if (const std::string dir = library_dir(); !dir.empty()) return {dir + "/" + file};
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) return {(self.parent_path() / file).string()};
  return {};
}

// The first of `candidates` that loads and has the entry point; `tried` collects why the
// others did not.
const ImageBackend* first_loading(const std::vector<std::string>& candidates, std::string& from,
                                  std::string& tried) {
  for (const std::string& path : candidates) {
    if (void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) {
      using Entry = const ImageBackend* (*)();
      if (auto entry = reinterpret_cast<Entry>(dlsym(module, kEntry))) {
        from = path;
        return entry();
      }
      tried += "\n  " + path + ": no " + kEntry;
      continue;
    }
    const char* why = dlerror();
    tried += "\n  " + path + ": " + (why ? why : "cannot load");
  }
  return nullptr;
}

LoadedBackend load_backend() {
  std::string from, tried;
  if (const char* env = std::getenv("RELIEFLAB_IMAGE_MODULE"); env && *env) {
    if (const ImageBackend* b = first_loading({env}, from, tried))
      return {b, std::string(b->name) + " from " + from + " (RELIEFLAB_IMAGE_MODULE)"};
    throw std::runtime_error("cannot load the image module RELIEFLAB_IMAGE_MODULE names:" + tried);
  }
  const auto oiio = module_candidates("librelieflab_oiio.so");
  if (const ImageBackend* b = first_loading(oiio, from, tried))
    return {b, std::string(b->name) + " from " + from};
  const std::string oiio_failures = tried;
  const auto stb = module_candidates("librelieflab_stb.so");
  if (const ImageBackend* b = first_loading(stb, from, tried))
    return {b, std::string(b->name) + " from " + from +
                   " (the fallback: OpenImageIO's module did not load:" + oiio_failures + ")"};
  throw std::runtime_error(
      "cannot load an image module (OpenImageIO, or the stb fallback); tried:" + tried);
}

const LoadedBackend& loaded() {
  static std::once_flag once;
  static LoadedBackend backend;
  std::call_once(once, [] { backend = load_backend(); });
  return backend;
}

}  // namespace

const ImageBackend& image_backend() {
  return *loaded().backend;
}

std::string image_backend_description() {
  return loaded().description;
}

std::string image_backend_name() {
  return loaded().backend->name;
}

}  // namespace rl
