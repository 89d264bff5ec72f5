#pragma once
// The output folder a run, a merge or a report writes into is the user's: a link planted in it
// under a name the run owns (run.log, results.sqlite, images/, ...) would send what the run
// writes somewhere else, and a folder or a device in place of a file would hang or fail it
// half-way. Checked before anything is written.
#include <string>

namespace rl {

// Throws ConfigError naming the entry when one of the names the run owns
// (config/config.h: run_owned_names) exists in `dir` as a symbolic link, or as something other
// than what the run writes there (a regular file, or a folder for images/, plots/, gbuffers/,
// report_assets/).
void check_run_folder(const std::string& dir);

// Held by every command that writes into a run folder (run, merge, report) from its checks to
// its last output: two at once into one folder would leave one sweep's sweep.json beside the
// other's rows. A second command waits, saying so on stderr, then runs on the folder as the
// first left it. An advisory lock (flock) on the folder itself, which no command can delete
// from under it, released when the process ends, however it ends.
class RunFolderLock {
 public:
  explicit RunFolderLock(const std::string& dir);
  ~RunFolderLock();
  RunFolderLock(const RunFolderLock&) = delete;
  RunFolderLock& operator=(const RunFolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace rl
