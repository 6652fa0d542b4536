#pragma once
// SQLite access for the store: prepared statements with typed binds and columns, opening a file, and the
// questions asked of a file before it is trusted as a store. Internal to engine/sweep/store.
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sqlite3.h>

#include "engine/common/error.hpp"
#include "engine/model/metrics.hpp"

namespace dampbench::sweep::store_db {

/// StoreError "store: <what>: <SQLite's message>".
[[noreturn]] void sql_fail(sqlite3* db, std::string_view what);

/// A prepared statement with positional binds (1-based) and typed columns (0-based).
class Stmt {
 public:
  Stmt(sqlite3* db, const char* sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql, -1, &s_, nullptr) != SQLITE_OK) sql_fail(db, sql);
  }
  ~Stmt() { sqlite3_finalize(s_); }
  Stmt(const Stmt&) = delete;
  Stmt& operator=(const Stmt&) = delete;

  Stmt& bind(int i, long long v) { return check(sqlite3_bind_int64(s_, i, v)); }
  Stmt& bind(int i, int v) { return check(sqlite3_bind_int64(s_, i, v)); }
  Stmt& bind(int i, double v) { return check(sqlite3_bind_double(s_, i, v)); }
  Stmt& bind(int i, const std::string& v) {
    return check(sqlite3_bind_text(s_, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT));
  }
  Stmt& bind_blob(int i, const void* data, std::size_t bytes) {
    // A zero-length blob binds as an empty blob, not NULL.
    return check(sqlite3_bind_blob(s_, i, bytes ? data : "", static_cast<int>(bytes), SQLITE_TRANSIENT));
  }
  Stmt& bind(int i, const std::vector<double>& v) { return bind_blob(i, v.data(), v.size() * sizeof(double)); }
  template <std::size_t N>
  Stmt& bind(int i, const std::array<double, N>& v) { return bind_blob(i, v.data(), N * sizeof(double)); }

  /// true while a row is available.
  bool step() {
    const int rc = sqlite3_step(s_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    sql_fail(db_, sqlite3_sql(s_));
  }
  void run() {
    step();
    sqlite3_reset(s_);
    sqlite3_clear_bindings(s_);
  }
  void reset() {
    sqlite3_reset(s_);
    sqlite3_clear_bindings(s_);
  }

  long long integer(int c) const { return sqlite3_column_int64(s_, c); }
  double real(int c) const {
    // SQLite stores NaN as NULL: read it back as NaN.
    return sqlite3_column_type(s_, c) == SQLITE_NULL ? std::nan("") : sqlite3_column_double(s_, c);
  }
  std::string text(int c) const {
    const auto* p = sqlite3_column_text(s_, c);
    return p ? std::string(reinterpret_cast<const char*>(p), static_cast<std::size_t>(sqlite3_column_bytes(s_, c))) : "";
  }
  std::vector<double> doubles(int c) const {
    // The blob first, then its size (SQLite's documented order). A damaged blob of fewer than 8 bytes gives no
    // double, and memcpy must not see the empty vector's null data then.
    const void* blob = sqlite3_column_blob(s_, c);
    std::vector<double> v(static_cast<std::size_t>(sqlite3_column_bytes(s_, c)) / sizeof(double));
    if (!v.empty()) std::memcpy(v.data(), blob, v.size() * sizeof(double));
    return v;
  }
  std::array<double, kMetricCount> metric_row(int c) const {
    std::array<double, kMetricCount> a{};
    const auto v = doubles(c);
    for (std::size_t i = 0; i < a.size() && i < v.size(); ++i) a[i] = v[i];
    return a;
  }

 private:
  Stmt& check(int rc) {
    if (rc != SQLITE_OK) sql_fail(db_, "bind");
    return *this;
  }
  sqlite3* db_;
  sqlite3_stmt* s_ = nullptr;
};

/// Column c of the row as the JSON of a T (the store writes lists and maps as JSON text); a value that is not
/// (a damaged store) is a StoreError naming the table and column, like every other damage a store can have.
template <class T>
T json_column(const Stmt& row, int c, std::string_view table_column) {
  try {
    return nlohmann::json::parse(row.text(c)).get<T>();
  } catch (const nlohmann::json::exception& e) {
    throw StoreError(fmt::format("store: {} holds no valid JSON of its kind (a damaged store?): {}", table_column, e.what()));
  }
}

/// Opens a SQLite file with a busy timeout; StoreError naming the path when it cannot.
sqlite3* open_db(const std::string& path, int flags);
int user_version(sqlite3* db);
bool has_table(sqlite3* db, const char* name);
/// A SQLite file without any table (a creation killed before its commit), or an empty file.
bool is_empty_database(const std::string& path);

}  // namespace dampbench::sweep::store_db
