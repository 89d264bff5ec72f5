#include "output/result_store.h"

#include <sqlite3.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include "core/columns.h"
#include "core/error.h"

namespace rl {
namespace {

void check(int rc, sqlite3* db, const std::string& what) {
  if (rc != SQLITE_OK && rc != SQLITE_DONE && rc != SQLITE_ROW)
    throw std::runtime_error(std::string("result store ") + sqlite3_db_filename(db, "main") + ": " +
                             what + ": " + sqlite3_errmsg(db));
}

// Runs setup SQL, retrying while another process holds the lock: a store being created or
// switched to WAL by one process answers SQLITE_BUSY to the others, and some of those paths
// bypass the busy handler. Up to about 5 s.
void exec_with_retry(sqlite3* db, const char* sql, const std::string& what) {
  int rc = SQLITE_OK;
  for (int attempt = 0; attempt < 500; ++attempt) {
    rc = sqlite3_exec(db, sql, nullptr, nullptr, nullptr);
    if (rc != SQLITE_BUSY && rc != SQLITE_LOCKED) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  check(rc, db, what);
}

struct Statement {
  sqlite3_stmt* s = nullptr;
  Statement(sqlite3* db, const char* sql) {
    check(sqlite3_prepare_v2(db, sql, -1, &s, nullptr), db, sql);
  }
  ~Statement() { sqlite3_finalize(s); }
};

// `path` as an SQLite URI with `query` ("mode=ro", "immutable=1"): the characters a URI
// gives meaning to are percent-encoded.
std::string sqlite_uri(const std::string& path, const char* query) {
  std::string out = "file:";
  for (unsigned char c : path) {
    if (c == '?' || c == '#' || c == '%' || c <= 0x20 || c >= 0x7F) {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      out += hex;
    } else {
      out += char(c);
    }
  }
  return out + "?" + query;
}

// Whether the store holds ReliefLab's table (an empty file or another database does not).
bool has_rows_table(sqlite3* db) {
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'rows'",
                         -1, &s, nullptr) != SQLITE_OK)
    return false;
  const bool found = sqlite3_step(s) == SQLITE_ROW;
  sqlite3_finalize(s);
  return found;
}

// Whether `schema`'s rows table has `column`.
bool has_column(sqlite3* db, const char* schema, const char* column) {
  const std::string sql = std::string("PRAGMA ") + schema + ".table_info(rows)";
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr) != SQLITE_OK) return false;
  bool found = false;
  while (!found && sqlite3_step(s) == SQLITE_ROW) {
    const unsigned char* name = sqlite3_column_text(s, 1);
    found = name && std::string(reinterpret_cast<const char*>(name)) == column;
  }
  sqlite3_finalize(s);
  return found;
}

// Opens `path` for reading only: as it is ("mode=ro", seeing rows a live run has not yet
// checkpointed), else, where even that needs a write (read-only media), as an unchanging file.
sqlite3* open_read_only(const std::string& path) {
  if (!std::filesystem::is_regular_file(path))
    throw ConfigError(path + ": no result store there (not a regular file)");
  for (const char* query : {"mode=ro", "immutable=1"}) {
    sqlite3* db = nullptr;
    const int rc = sqlite3_open_v2(sqlite_uri(path, query).c_str(), &db,
                                   SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr);
    if (rc == SQLITE_OK && has_rows_table(db)) return db;
    const bool readable = rc == SQLITE_OK && sqlite3_exec(db, "SELECT count(*) FROM sqlite_master",
                                                          nullptr, nullptr, nullptr) == SQLITE_OK;
    sqlite3_close(db);
    if (readable)
      throw ConfigError(path + ": not a ReliefLab result store (it holds no rows table)");
  }
  throw ConfigError(path + ": cannot read the result store (not an SQLite database?)");
}

}  // namespace

ResultStore::ResultStore(const std::string& path, Access access) : path_(path) {
  if (access == Access::ReadOnly) {
    db_ = open_read_only(path);
    return;
  }
  if (sqlite3_open(path.c_str(), &db_) != SQLITE_OK) {
    std::string msg = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw std::runtime_error("cannot open result store " + path + ": " + msg);
  }
  sqlite3_busy_timeout(db_, 5000);
  exec_with_retry(db_, "PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL;", "pragmas");
  exec_with_retry(db_,
                  "CREATE TABLE IF NOT EXISTS rows ("
                  " key TEXT PRIMARY KEY,"
                  " row TEXT NOT NULL,"
                  " written_at TEXT DEFAULT CURRENT_TIMESTAMP,"
                  " programs TEXT)",
                  "create table");
  // A store made before rows recorded their programs gains the column; its rows have none, so
  // a run measures them again (run/cell_provenance.h).
  if (!has_column(db_, "main", "programs"))
    exec_with_retry(db_, "ALTER TABLE rows ADD COLUMN programs TEXT", "add the programs column");
}

ResultStore::~ResultStore() {
  sqlite3_close(db_);
}

std::set<std::string> ResultStore::keys() const {
  std::set<std::string> out;
  Statement st(db_, "SELECT key FROM rows");
  // A damaged file can hold a NULL where the schema forbids one (found by test_fuzz).
  while (sqlite3_step(st.s) == SQLITE_ROW)
    if (const unsigned char* key = sqlite3_column_text(st.s, 0))
      out.insert(reinterpret_cast<const char*>(key));
  return out;
}

std::optional<nlohmann::ordered_json> ResultStore::row(const std::string& key) const {
  Statement st(db_, "SELECT row FROM rows WHERE key = ?");
  sqlite3_bind_text(st.s, 1, key.c_str(), -1, SQLITE_TRANSIENT);
  if (sqlite3_step(st.s) != SQLITE_ROW) return std::nullopt;
  const unsigned char* text = sqlite3_column_text(st.s, 0);
  if (!text) return std::nullopt;  // a NULL row in a damaged file: as good as missing
  return nlohmann::ordered_json::parse(reinterpret_cast<const char*>(text));
}

std::string ResultStore::programs(const std::string& key) const {
  if (!has_column(db_, "main", "programs")) return "";  // a read-only store of before
  Statement st(db_, "SELECT programs FROM rows WHERE key = ?");
  sqlite3_bind_text(st.s, 1, key.c_str(), -1, SQLITE_TRANSIENT);
  if (sqlite3_step(st.s) != SQLITE_ROW) return "";
  const unsigned char* text = sqlite3_column_text(st.s, 0);
  return text ? reinterpret_cast<const char*>(text) : "";
}

void ResultStore::insert(const std::string& key, const nlohmann::ordered_json& row) {
  Statement st(db_, "INSERT OR IGNORE INTO rows (key, row) VALUES (?, ?)");
  const std::string text = row.dump();
  sqlite3_bind_text(st.s, 1, key.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(st.s, 2, text.c_str(), -1, SQLITE_TRANSIENT);
  check(sqlite3_step(st.s), db_, "insert row");
}

void ResultStore::put(const std::string& key, const nlohmann::ordered_json& row,
                      const std::string& programs, const std::string& replacing) {
  if (!replacing.empty() && replacing != key) {
    check(sqlite3_exec(db_, "BEGIN IMMEDIATE", nullptr, nullptr, nullptr), db_, "begin");
    try {
      put(key, row, programs);
      erase(replacing);
    } catch (...) {
      sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
      throw;
    }
    check(sqlite3_exec(db_, "COMMIT", nullptr, nullptr, nullptr), db_, "commit");
    return;
  }
  Statement st(db_,
               "INSERT OR REPLACE INTO rows (key, row, written_at, programs) VALUES (?, ?, "
               "CURRENT_TIMESTAMP, ?)");
  const std::string text = row.dump();
  sqlite3_bind_text(st.s, 1, key.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(st.s, 2, text.c_str(), -1, SQLITE_TRANSIENT);
  if (programs.empty())
    sqlite3_bind_null(st.s, 3);
  else
    sqlite3_bind_text(st.s, 3, programs.c_str(), -1, SQLITE_TRANSIENT);
  check(sqlite3_step(st.s), db_, "store row");
}

void ResultStore::erase(const std::string& key) {
  Statement st(db_, "DELETE FROM rows WHERE key = ?");
  sqlite3_bind_text(st.s, 1, key.c_str(), -1, SQLITE_TRANSIENT);
  check(sqlite3_step(st.s), db_, "delete row");
}

size_t ResultStore::merge_from(const std::string& other_path) {
  {
    const ResultStore other(other_path, Access::ReadOnly);  // throws naming a non-store
  }
  Statement attach(db_, "ATTACH DATABASE ? AS other");
  sqlite3_bind_text(attach.s, 1, other_path.c_str(), -1, SQLITE_TRANSIENT);
  check(sqlite3_step(attach.s), db_, "attach " + other_path);
  const int before = sqlite3_total_changes(db_);
  // A shard's store made before rows recorded their programs has no such column.
  const std::string sql =
      std::string(
          "INSERT OR IGNORE INTO rows (key, row, written_at, programs) SELECT key, row, "
          "written_at, ") +
      (has_column(db_, "other", "programs") ? "programs" : "NULL") + " FROM other.rows";
  check(sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr), db_, "merge");
  const size_t merged = size_t(sqlite3_total_changes(db_) - before);
  check(sqlite3_exec(db_, "DETACH DATABASE other", nullptr, nullptr, nullptr), db_, "detach");
  return merged;
}

bool store_creation_cut_short(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  if (std::filesystem::file_size(path, ec) == 0 && !ec) return true;
  sqlite3* db = nullptr;
  bool empty = false;
  if (sqlite3_open_v2(sqlite_uri(path, "mode=ro").c_str(), &db,
                      SQLITE_OPEN_READONLY | SQLITE_OPEN_URI, nullptr) == SQLITE_OK) {
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db, "SELECT count(*) FROM sqlite_master", -1, &s, nullptr) ==
            SQLITE_OK &&
        sqlite3_step(s) == SQLITE_ROW)
      empty = sqlite3_column_int(s, 0) == 0;
    sqlite3_finalize(s);
  }
  sqlite3_close(db);
  return empty;
}

std::string stored_value_outside_range(const nlohmann::ordered_json& row) {
  if (!row.is_object()) return "";
  for (const DeclaredColumn& c : declared_columns()) {
    if (c.spec.kind != ColumnKind::Number) continue;
    auto it = row.find(c.spec.name);
    if (it == row.end() || !it->is_number()) continue;
    if (const std::string why = value_outside_range(c.spec, it->get<double>()); !why.empty())
      return "holds a value in '" + c.spec.name + "' its column cannot take: " + why;
  }
  return "";
}

}  // namespace rl
