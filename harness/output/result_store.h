#pragma once
// The result store: one SQLite database per output folder, one row per sweep cell keyed by a
// stable hash of what the config varies (run/cells.h), each row naming what it was measured
// from (its `measured_from` column) with the programs it drew with beside it
// (output/provenance.h). Each row is committed in its own transaction (WAL journal), so a sweep
// killed midway loses at most the cell in flight, and a re-run reuses every row measured from
// what it has now: nothing is redone, nothing duplicated, nothing stale kept. Stores from shards
// run elsewhere merge by key.
#include <map>
#include <optional>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

struct sqlite3;

namespace rl {

class ResultStore {
 public:
  // ReadOnly: status, compare and report, which only read, open the store without creating or
  // locking anything, so a run on read-only media (an archive, a mounted snapshot) reads; a
  // file that is not a ReliefLab store (no rows table: an empty or foreign file) throws
  // ConfigError naming it.
  enum class Access { ReadWrite, ReadOnly };
  explicit ResultStore(const std::string& path, Access access = Access::ReadWrite);
  ~ResultStore();
  ResultStore(const ResultStore&) = delete;
  ResultStore& operator=(const ResultStore&) = delete;

  std::set<std::string> keys() const;
  std::optional<nlohmann::ordered_json> row(const std::string& key) const;
  // The programs the row of `key` was drawn with (run/cell_provenance.h), "" when the store has
  // none for it (a row stored before they were recorded).
  std::string programs(const std::string& key) const;
  // Inserts the row; an existing key is left untouched (first result wins).
  void insert(const std::string& key, const nlohmann::ordered_json& row);
  // Stores the row and its programs under `key`, replacing a row already there (one measured
  // from other code or inputs) in one statement: a kill leaves the old row or the new one,
  // never a mix.
  // With `replacing`, the row stored under that older key (the same cell before its key
  // changed) is removed in the same transaction.
  void put(const std::string& key, const nlohmann::ordered_json& row,
           const std::string& programs = "", const std::string& replacing = "");
  // Removes a row (one found corrupt, so that its cell is measured again).
  void erase(const std::string& key);
  // Copies every row of another store whose key this one lacks; returns how many. Throws
  // ConfigError naming `other_path` when it is not a ReliefLab store.
  size_t merge_from(const std::string& other_path);

 private:
  sqlite3* db_ = nullptr;
  std::string path_;
};

// Whether `path` is a store whose creation was cut short: an empty file, or an SQLite file that
// holds no table yet (what a command killed while it made the store leaves); such a store is
// made again, not refused as "not a ReliefLab result store".
bool store_creation_cut_short(const std::string& path);

// "" when every number a stored row holds is one its column can take (core/columns.h:
// column_range); else "holds a value in 'COLUMN' its column cannot take: WHY". A row edited or
// damaged in the store is neither reused, published nor compared with such a value.
std::string stored_value_outside_range(const nlohmann::ordered_json& row);

}  // namespace rl
