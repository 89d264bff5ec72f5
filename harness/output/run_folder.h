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

// run.log's first line opens with the sweep and the config it ran from ("relieflab: sweep 'NAME'
// from SOURCE: N cells ..."): written by the run, read back by `verify` to find a folder's config.
std::string sweep_log_line_start(const std::string& name, const std::string& source);
// The SOURCE such a line names; "" when `first_line` is not one.
std::string sweep_log_source(const std::string& first_line);

}  // namespace rl
