#include "output/run_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <regex>

#include "config/config.h"
#include "core/error.h"

namespace rl {
namespace {

// Nothing the run writes may go through a link: a planted images/<scene> or a picture's name
// linked elsewhere would have it write into another folder.
void check_no_links_below(const std::filesystem::path& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_symlink(ec))
      throw ConfigError(it->path().string() +
                        " is a symbolic link: a run writes its own files in its output folder "
                        "and follows no link there (remove it, or choose another --out)");
  if (ec) throw ConfigError(folder.string() + ": cannot be read (" + ec.message() + ")");
}

}  // namespace

void check_run_folder(const std::string& dir) {
  namespace fs = std::filesystem;
  for (const std::string& name : run_owned_names()) {
    const fs::path p = fs::path(dir) / name;
    std::error_code ec;
    const fs::file_status st = fs::symlink_status(p, ec);
    if (ec || !fs::exists(st)) continue;
    if (fs::is_symlink(st))
      throw ConfigError(p.string() +
                        " is a symbolic link: a run writes its own files in its output folder "
                        "and follows no link there (remove it, or choose another --out)");
    const bool folder = name.find('.') == std::string::npos;  // images, plots, gbuffers, ...
    if (folder ? !fs::is_directory(st) : !fs::is_regular_file(st))
      throw ConfigError(p.string() + " is not a " + (folder ? "folder" : "regular file") +
                        ": the run writes its own " + (folder ? "folder" : "file") +
                        " there (remove it, or choose another --out)");
    if (folder) check_no_links_below(p);
  }
}

RunFolderLock::RunFolderLock(const std::string& dir) {
  // The folder itself, not a file in it: a lock file deleted during a run let a second command
  // lock a new one and write into the folder beside the first, and it stayed behind after.
  const std::string& path = dir;
  fd_ = open(path.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd_ < 0)
    throw ConfigError(path + ": cannot open the run folder to lock it (" + std::strerror(errno) +
                      ")");
  if (flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
  if (errno != EWOULDBLOCK) {
    // A file system without locks (some network mounts): the run goes on, unguarded, and
    // says so rather than refusing a folder it could always write before.
    std::fprintf(stderr,
                 "relieflab: warning: %s cannot be locked (%s): nothing keeps another command "
                 "from writing into %s at the same time\n",
                 path.c_str(), std::strerror(errno), dir.c_str());
    return;
  }
  std::fprintf(stderr,
               "relieflab: waiting for another relieflab command writing into %s to finish\n",
               dir.c_str());
  while (flock(fd_, LOCK_EX) != 0)
    if (errno != EINTR) {
      const int e = errno;
      close(fd_);
      throw ConfigError(path + ": cannot lock (" + std::strerror(e) + ")");
    }
}

RunFolderLock::~RunFolderLock() {
  if (fd_ >= 0) close(fd_);  // releases the lock
}

std::string sweep_log_line_start(const std::string& name, const std::string& source) {
  return "relieflab: sweep '" + name + "' from " + source + ": ";
}

std::string sweep_log_source(const std::string& first_line) {
  static const std::regex line(R"(^relieflab: sweep '.*' from (.+): \d+ cells)");
  std::smatch m;
  return std::regex_search(first_line, m, line) ? m[1].str() : "";
}

}  // namespace rl
