#include "core/code_digest.h"

#include <sys/stat.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>

#include "core/hash.h"

namespace rl {
namespace {

namespace fs = std::filesystem;

std::mutex& digests_mutex() {
  static std::mutex m;
  return m;
}

std::map<std::string, std::string>& plugin_folders() {
  static std::map<std::string, std::string> folders;
  return folders;
}

// The source root as this library was built from it, ending in '/'.
const std::string& source_root() {
  static const std::string root = fs::path(RELIEFLAB_SOURCE_DIR).lexically_normal().string() + "/";
  return root;
}

}  // namespace

std::string code_digest(std::initializer_list<const char*> folders) {
  std::string text = build_settings_digest();
  for (const char* folder : folders) {
    auto it = source_digests().find(folder);
    if (it == source_digests().end())
      throw std::logic_error(std::string("code_digest: the build digests no folder '") + folder +
                             "'");
    text += std::string("|") + folder + "=" + it->second;
  }
  return hex64(fnv1a64(text));
}

std::string source_folder(const std::string& source_file) {
  const std::string folder = fs::path(source_file).lexically_normal().parent_path().string();
  const std::string& root = source_root();
  if (folder.compare(0, root.size(), root) == 0) return folder.substr(root.size());
  return folder;
}

std::string folder_digest(const std::string& folder) {
  if (source_digests().count(folder)) return code_digest({folder.c_str()});
  const std::lock_guard<std::mutex> lock(digests_mutex());
  auto it = plugin_folders().find(folder);
  return it == plugin_folders().end() ? "" : it->second;
}

void register_folder_digest(const std::string& folder, const std::string& digest) {
  const std::lock_guard<std::mutex> lock(digests_mutex());
  plugin_folders()[folder] = digest;
}

std::string precompute_code_digest(const std::source_location& where) {
  static const std::string harness =
      code_digest({"harness/core", "harness/gl", "harness/relief", "harness/scene", "harness/truth",
                   "harness/gpu", "harness/technique"});
  const std::string folder = source_folder(where.file_name());
  const std::string own = folder_digest(folder);
  // A caller the build cannot place (neither its tree nor a loaded plugin's) is named by its
  // file: its entries are then never shared with another build's, only with its own.
  return hex64(fnv1a64(harness + "|" + (own.empty() ? std::string(where.file_name()) : own)));
}

namespace {

struct FileStamp {
  uintmax_t size = 0;
  int64_t mtime_ns = 0;
  std::string digest;
};

std::map<std::string, FileStamp>& file_memo() {
  static std::map<std::string, FileStamp> memo;
  return memo;
}

uint64_t& reads() {
  static uint64_t n = 0;
  return n;
}

}  // namespace

std::string file_digest(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return "";
  const int64_t mtime_ns = int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
  {
    const std::lock_guard<std::mutex> lock(digests_mutex());
    auto it = file_memo().find(path);
    if (it != file_memo().end() && it->second.size == uintmax_t(st.st_size) &&
        it->second.mtime_ns == mtime_ns)
      return it->second.digest;
  }
  const std::string digest = hex64(file_content_hash(path));
  const std::lock_guard<std::mutex> lock(digests_mutex());
  ++reads();
  // The stamp taken before the read: a file rewritten while it was read is read again next time.
  file_memo()[path] = {uintmax_t(st.st_size), mtime_ns, digest};
  return digest;
}

uint64_t file_digest_reads() {
  const std::lock_guard<std::mutex> lock(digests_mutex());
  return reads();
}

}  // namespace rl
