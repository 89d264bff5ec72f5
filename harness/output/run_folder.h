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

}  // namespace rl
