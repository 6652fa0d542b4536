#include "engine/sweep/store/sqlite_access.hpp"

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench::sweep::store_db {

void sql_fail(sqlite3* db, std::string_view what) {
  throw StoreError(fmt::format("store: {}: {}", what, db ? sqlite3_errmsg(db) : "out of memory"));
}

sqlite3* open_db(const std::string& path, int flags) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, flags, nullptr) != SQLITE_OK) {
    const std::string msg = db ? sqlite3_errmsg(db) : "out of memory";
    sqlite3_close(db);
    throw StoreError(fmt::format("cannot open store '{}': {}", path, msg));
  }
  sqlite3_busy_timeout(db, 10000);
  return db;
}

int user_version(sqlite3* db) {
  Stmt s(db, "PRAGMA user_version");
  s.step();
  return static_cast<int>(s.integer(0));
}

bool has_table(sqlite3* db, const char* name) {
  Stmt s(db, "SELECT 1 FROM sqlite_master WHERE type='table' AND name=?");
  s.bind(1, std::string(name));
  return s.step();
}

bool is_empty_database(const std::string& path) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    return false;
  }
  bool empty = false;
  sqlite3_stmt* s = nullptr;
  if (sqlite3_prepare_v2(db, "SELECT COUNT(*) FROM sqlite_master", -1, &s, nullptr) == SQLITE_OK && sqlite3_step(s) == SQLITE_ROW)
    empty = sqlite3_column_int64(s, 0) == 0;
  sqlite3_finalize(s);
  sqlite3_close(db);
  return empty;
}

}  // namespace dampbench::sweep::store_db
