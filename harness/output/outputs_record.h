#pragma once
// outputs.json: the files a run wrote into its folder (rows.csv, its tables, pareto.md, the
// report but for its verdict panel) with each file's content digest; rows.csv must be among
// them, and neither the record nor a file it lists may be a link. Written by the producer of
// the rows, never by a check: an edit
// made to rows.csv or a table afterwards is told from what the run wrote, and `relieflab
// verify --write` refuses to regenerate verdicts from such rows (it would launder them while
// the tables and the report still showed the run's numbers).
#include <map>
#include <string>
#include <vector>

namespace rl {

// Digest of a file's bytes as outputs.json records it ("fnv1a64:" + 16 hex digits).
std::string content_digest(const std::string& bytes);

// Writes DIR/outputs.json naming `files` (names in DIR) with the digests of their contents.
void write_outputs_record(const std::string& dir, const std::map<std::string, std::string>& files);

// What differs between DIR's files and its outputs.json, a line each: a file edited since it
// was written, one listed but missing, or no record at all. Empty when every file is as written.
std::vector<std::string> outputs_record_differences(const std::string& dir);

}  // namespace rl
