#include "output/outputs_record.h"

#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/hash.h"
#include "output/report.h"

namespace rl {

// The published FNV-1a offset basis, so that any tool can check a digest (scripts/
// outputs_record.py does). core/hash.h's keys start from another one (a digit short of it),
// kept there because every stored cell key depends on it.
constexpr uint64_t kFnvOffsetBasis = 14695981039346656037ull;

std::string content_digest(const std::string& bytes) {
  return "fnv1a64:" + hex64(fnv1a64(bytes.data(), bytes.size(), kFnvOffsetBasis));
}

namespace {

// What a file's digest is taken over: its bytes; for the report, with the verdict panel left
// out, which `relieflab verify --write` fills from the claims after the run (and checks against
// them on its own), and its style and scripts named as the run named them (a results tree keeps
// one copy of them for every folder: scripts/reproduce.sh).
std::string recorded_digest(const std::string& name, const std::string& bytes) {
  if (name != "report.html") return content_digest(bytes);
  std::string page = bytes;
  set_report_verdicts(page, nullptr);
  const std::string shared = "\"../report_assets/", own = "\"report_assets/";
  for (size_t at = page.find(shared); at != std::string::npos; at = page.find(shared, at))
    page.replace(at, shared.size(), own);
  return content_digest(page);
}

}  // namespace

void write_outputs_record(const std::string& dir, const std::map<std::string, std::string>& files) {
  nlohmann::ordered_json record = {
      {"about",
       "the files relieflab wrote here, with the digests of their contents (FNV-1a, 64 bits): "
       "relieflab verify refuses a folder whose files differ from them"},
      {"files", nlohmann::ordered_json::object()}};
  for (const auto& [name, bytes] : files) record["files"][name] = recorded_digest(name, bytes);
  write_text_atomic(dir + "/outputs.json", record.dump(2) + "\n");
}

std::vector<std::string> outputs_record_differences(const std::string& dir) {
  const std::string path = dir + "/outputs.json";
  // A link would stand another folder's record (or rows) in for this one's.
  if (std::filesystem::is_symlink(path))
    return {path + ": a link, not the record this folder's run wrote; refused"};
  if (!std::filesystem::exists(path))
    return {path +
            ": missing: the digests of what the run wrote, against which its rows are checked "
            "(regenerate the folder with scripts/reproduce.sh)"};
  nlohmann::json record;
  try {
    record = nlohmann::json::parse(read_text(path));
    if (!record["files"].is_object() || record["files"].empty())
      throw std::runtime_error("no 'files'");
  } catch (const std::exception& e) {
    return {path + ": unreadable (" + std::string(e.what()).substr(0, 120) + ")"};
  }
  std::vector<std::string> out;
  // The rows are what every verdict reads: a record that leaves them out checks nothing.
  if (std::filesystem::exists(dir + "/rows.csv") && !record["files"].contains("rows.csv"))
    out.push_back(path +
                  ": does not list rows.csv, whose rows the verdicts read: not the record "
                  "a run writes; refused");
  for (const auto& [name, digest] : record["files"].items()) {
    const std::string file = dir + "/" + name;
    if (name.find('/') != std::string::npos || name.find("..") != std::string::npos) {
      out.push_back(path + ": names '" + name + "', not a file of the folder");
    } else if (std::filesystem::is_symlink(file)) {
      out.push_back(file + ": a link, not the file the run wrote; refused");
    } else if (!std::filesystem::is_regular_file(file)) {
      out.push_back(file + ": listed in outputs.json but missing");
    } else if (!digest.is_string() ||
               digest.get<std::string>() != recorded_digest(name, read_text(file))) {
      out.push_back(file +
                    ": differs from what the run wrote (outputs.json): edited since? A "
                    "verdict is regenerated only from a run's own rows: run it again "
                    "(scripts/reproduce.sh), nothing was rewritten");
    }
  }
  return out;
}

}  // namespace rl
