#include "claims/tables_follow_rows.h"

#include <filesystem>

#include "config/config.h"
#include "core/atomic_write.h"
#include "core/error.h"
#include "output/rows_csv.h"
#include "output/run_folder.h"
#include "output/tables.h"

namespace rl {
namespace fs = std::filesystem;
namespace {

// The config path run.log's first line names (output/run_folder.h).
std::string run_log_config(const std::string& dir) {
  const fs::path log = fs::path(dir) / "run.log";
  if (!fs::is_regular_file(log)) return "";
  const std::string text = read_text(log.string());
  return sweep_log_source(text.substr(0, text.find('\n')));
}

// The line at which two texts first differ, each side quoted, for a message.
std::string first_difference(const std::string& file, const std::string& laid_out) {
  size_t at = 0, line = 1;
  while (at < file.size() && at < laid_out.size() && file[at] == laid_out[at])
    if (file[at++] == '\n') ++line;
  auto line_at = [](const std::string& s, size_t pos) {
    const size_t begin = s.rfind('\n', pos == 0 ? 0 : pos - 1);
    const size_t from = begin == std::string::npos || pos == 0 ? 0 : begin + 1;
    return s.substr(from, std::min<size_t>(s.find('\n', from) - from, 160));
  };
  return "line " + std::to_string(line) + " reads '" + line_at(file, at) + "', rows.csv gives '" +
         line_at(laid_out, at) + "'";
}

}  // namespace

std::string folder_config_path(const std::string& dir) {
  if (fs::is_regular_file(fs::path(dir) / "config.toml"))
    return (fs::path(dir) / "config.toml").string();
  const std::string named = run_log_config(dir);
  if (named.empty()) return "";
  fs::path folder = fs::absolute(dir).lexically_normal();
  if (!folder.has_filename()) folder = folder.parent_path();  // "results/name/"
  const fs::path repository = folder.parent_path().parent_path();
  // A path the run took on another machine still names the repository's configs/ folder.
  const size_t configs = named.rfind("configs/");
  std::vector<fs::path> candidates;
  if (configs != std::string::npos) candidates.push_back(repository / named.substr(configs));
  candidates.push_back(repository / named);
  candidates.push_back(named);
  for (const fs::path& c : candidates)
    if (fs::is_regular_file(c)) return c.string();
  return candidates.front().string();
}

int verify_tables_follow_rows(const std::string& dir, std::string& report) {
  const std::string config_path = folder_config_path(dir);
  if (config_path.empty() || !fs::is_regular_file(fs::path(dir) / "rows.csv")) return 0;
  SweepConfig config;
  try {
    config = load_sweep_config(config_path);
  } catch (const std::exception& e) {
    report +=
        dir + ": its config " + config_path + " (run.log) no longer loads: " + e.what() + "\n";
    return 1;
  }
  const std::vector<Row> rows = rows_as_values(read_rows_csv(dir + "/rows.csv"));
  int failures = 0;
  for (const TableSpec& t : config.tables) {
    const std::string path = dir + "/" + t.file;
    if (!fs::is_regular_file(path)) continue;  // a folder keeps the tables it chose to
    const std::string file = read_text(path), laid_out = format_table_file(rows, t);
    if (file == laid_out) continue;
    report += path + ": does not follow from rows.csv under the [[table]] of " + config_path +
              " (" + first_difference(file, laid_out) +
              "): rows.csv was edited under it, or the config or the table code changed since "
              "the run (run it again)\n";
    ++failures;
  }
  return failures;
}

}  // namespace rl
