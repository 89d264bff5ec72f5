#pragma once
// Whether a result folder's tables follow from its rows.csv: each [[table]] of the config the
// folder was run from is laid out again from rows.csv (output/tables.h) and must read as the
// folder's file does. outputs.json tells an edit from what the run wrote only while its digests
// are the run's; a rows.csv edited and its digest recomputed still disagrees with the tables.
#include <string>

namespace rl {

// The config a folder was run from: its config.toml, else the file the first line of its
// run.log names, looked for under the repository that holds the folder (DIR/../..), then as
// named. "" when the folder names none (rows made by a program rather than a sweep).
std::string folder_config_path(const std::string& dir);

// A line per table of DIR that does not follow from DIR/rows.csv (or per config that no longer
// loads) appended to `report`; returns their number.
int verify_tables_follow_rows(const std::string& dir, std::string& report);

}  // namespace rl
