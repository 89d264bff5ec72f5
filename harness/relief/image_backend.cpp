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

const ImageBackend* load_backend() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("RELIEFLAB_IMAGE_MODULE"); env && *env)
    candidates.push_back(env);
  // Beside the libraries: in the build folder, or <prefix>/lib when installed.
  if (const std::string dir = library_dir(); !dir.empty())
    candidates.push_back(dir + "/librelieflab_oiio.so");
#ifdef RELIEFLAB_IMAGE_MODULE
  candidates.push_back(RELIEFLAB_IMAGE_MODULE);
#endif
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back((self.parent_path() / "librelieflab_oiio.so").string());
  std::string tried;
  for (const std::string& path : candidates) {
    if (void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) {
      using Entry = const ImageBackend* (*)();
      if (auto entry = reinterpret_cast<Entry>(dlsym(module, kEntry))) return entry();
      tried += "\n  " + path + ": no " + kEntry;
      continue;
    }
    const char* why = dlerror();
    tried += "\n  " + path + ": " + (why ? why : "cannot load");
  }
  throw std::runtime_error("cannot load the image module (OpenImageIO); tried:" + tried);
}

}  // namespace

const ImageBackend& image_backend() {
  static std::once_flag once;
  static const ImageBackend* backend = nullptr;
  std::call_once(once, [] { backend = load_backend(); });
  return *backend;
}

}  // namespace rl
