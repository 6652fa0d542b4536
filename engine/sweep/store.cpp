#include "engine/sweep/store.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sqlite3.h>

#include "engine/common/error.hpp"
#include "engine/sweep/fingerprint.hpp"

namespace dampbench::sweep {

static_assert(std::endian::native == std::endian::little, "store blobs are little-endian doubles");

namespace {

using json = nlohmann::json;

[[noreturn]] void sql_fail(sqlite3* db, std::string_view what) {
  throw StoreError(fmt::format("store: {}: {}", what, db ? sqlite3_errmsg(db) : "out of memory"));
}

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
    const int bytes = sqlite3_column_bytes(s_, c);
    std::vector<double> v(static_cast<std::size_t>(bytes) / sizeof(double));
    if (bytes) std::memcpy(v.data(), sqlite3_column_blob(s_, c), v.size() * sizeof(double));
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

constexpr const char* kSchema = R"sql(
CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE parts(part INTEGER PRIMARY KEY, name TEXT, title TEXT, path TEXT, source TEXT, seed INTEGER, runs INTEGER);
CREATE TABLE models(part INTEGER, model INTEGER, name TEXT, model_id TEXT, fixture TEXT, laws TEXT, bounds TEXT,
                    params TEXT, PRIMARY KEY(part, model));
CREATE TABLE optimizers(part INTEGER, optimizer INTEGER, label TEXT, name TEXT, population INTEGER, iterations INTEGER,
                        settings TEXT, PRIMARY KEY(part, optimizer));
CREATE TABLE splits(part INTEGER, split INTEGER, name TEXT, PRIMARY KEY(part, split));
CREATE TABLE datasets(part INTEGER, dataset INTEGER, name TEXT, collection TEXT, label TEXT, path TEXT, samples INTEGER,
                      hash TEXT, variables TEXT, error TEXT, PRIMARY KEY(part, dataset));
CREATE TABLE fitsets(part INTEGER, split INTEGER, fitset INTEGER, label TEXT, fit TEXT, predict TEXT,
                     PRIMARY KEY(part, split, fitset));
CREATE TABLE groups(grp INTEGER PRIMARY KEY, part INTEGER, split INTEGER, fitset INTEGER, model INTEGER,
                    optimizer INTEGER, metric TEXT, runs INTEGER, task_key TEXT, status TEXT, message TEXT,
                    wall_time_s REAL, candidate_samples REAL, evaluations INTEGER, dampbench_version TEXT,
                    build_flags TEXT, spec_hash TEXT, dataset_hash TEXT, finished_at TEXT);
CREATE TABLE runs(grp INTEGER, run INTEGER, best_value REAL, metrics BLOB, params BLOB, evaluations INTEGER,
                  stop_reason TEXT, trace BLOB, local_optimum INTEGER, PRIMARY KEY(grp, run)) WITHOUT ROWID;
CREATE TABLE dataset_metrics(grp INTEGER, run INTEGER, dataset INTEGER, role TEXT, metrics BLOB,
                             PRIMARY KEY(grp, run, dataset)) WITHOUT ROWID;
CREATE TABLE sensitivity(grp INTEGER PRIMARY KEY, dataset INTEGER, S BLOB, SP BLOB);
CREATE TABLE identifiability(grp INTEGER PRIMARY KEY, samples INTEGER, std_error BLOB, relative_error BLOB,
                             correlation BLOB, flags TEXT);
)sql";

std::vector<double> trace_blob(const std::vector<TracePoint>& trace) {
  std::vector<double> v;
  v.reserve(2 * trace.size());
  for (const auto& p : trace) {
    v.push_back(std::bit_cast<double>(static_cast<std::uint64_t>(p.evaluations)));
    v.push_back(p.value);
  }
  return v;
}

std::vector<TracePoint> trace_points(const std::vector<double>& v) {
  std::vector<TracePoint> t(v.size() / 2);
  for (std::size_t i = 0; i < t.size(); ++i)
    t[i] = {static_cast<long long>(std::bit_cast<std::uint64_t>(v[2 * i])), v[2 * i + 1]};
  return t;
}

std::string now_utc() {
  const auto t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
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

/// A SQLite file without any table (a creation killed before its commit), or an empty file.
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

long long count(const std::string& text) { return text.empty() ? 0 : std::stoll(text); }

/// The metrics a run records, in blob order ("of_abs,of_sq,..."): a store is read with the same list.
std::string metric_list() {
  std::string s;
  for (Metric m : kAllMetrics) {
    if (!s.empty()) s += ',';
    s += metric_name(m);
  }
  return s;
}

}  // namespace

int GroupRecord::best_run() const {
  int best = run_results.empty() ? -1 : 0;
  for (int r = 1; r < static_cast<int>(run_results.size()); ++r)
    if (run_results[r].best_value < run_results[best].best_value) best = r;
  return best;
}

int StoreHeader::model(int part, int i) const {
  for (int k = 0, n = 0; k < static_cast<int>(models.size()); ++k)
    if (models[k].part == part && n++ == i) return k;
  return -1;
}
int StoreHeader::optimizer(int part, int i) const {
  for (int k = 0, n = 0; k < static_cast<int>(optimizers.size()); ++k)
    if (optimizers[k].part == part && n++ == i) return k;
  return -1;
}
int StoreHeader::dataset(int part, int i) const {
  // Datasets are stored part by part: find the part's first, then offset.
  for (int k = 0; k < static_cast<int>(datasets.size()); ++k)
    if (datasets[k].part == part) {
      const int j = k + i;
      return j < static_cast<int>(datasets.size()) && datasets[j].part == part ? j : -1;
    }
  return -1;
}
int StoreHeader::fitset(int part, int split, int i) const {
  for (int k = 0; k < static_cast<int>(fitsets.size()); ++k)
    if (fitsets[k].part == part && fitsets[k].split == split) {
      const int j = k + i;
      return j < static_cast<int>(fitsets.size()) && fitsets[j].part == part && fitsets[j].split == split ? j : -1;
    }
  return -1;
}
std::string StoreHeader::split_name(int part, int i) const {
  for (int k = 0, n = 0; k < static_cast<int>(splits.size()); ++k)
    if (splits[k].first == part && n++ == i) return splits[k].second;
  return "";
}

Store::Store(Store&& o) noexcept : db_(o.db_), path_(std::move(o.path_)) { o.db_ = nullptr; }
Store& Store::operator=(Store&& o) noexcept {
  if (this != &o) {
    sqlite3_close(db_);
    db_ = o.db_;
    path_ = std::move(o.path_);
    o.db_ = nullptr;
  }
  return *this;
}
Store::~Store() { sqlite3_close(db_); }

void Store::exec(const char* sql) const {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql, nullptr, nullptr, &err) != SQLITE_OK) {
    const std::string msg = err ? err : "?";
    sqlite3_free(err);
    throw StoreError(fmt::format("store '{}': {}", path_, msg));
  }
}

std::string Store::meta(const std::string& key) const {
  Stmt s(db_, "SELECT value FROM meta WHERE key=?");
  s.bind(1, key);
  return s.step() ? s.text(0) : "";
}

Store Store::open(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw StoreError(fmt::format("no store at '{}'", path));
  Store store(open_db(path, SQLITE_OPEN_READWRITE), path);
  int version = 0;
  try {
    version = user_version(store.db_);
    if (!has_table(store.db_, "meta")) version = -1;
  } catch (const std::runtime_error&) {
    version = -1;
  }
  if (version == -1 || (version == 0)) throw StoreError(fmt::format("'{}' is not a dampbench store", path));
  if (version != kStoreFormat)
    throw StoreError(fmt::format("store '{}' has format {}, this dampbench ({}) reads format {}", path, version,
                                 dampbench_version(), kStoreFormat));
  if (const std::string metrics = store.meta("metrics"); metrics != metric_list())
    throw StoreError(fmt::format("store '{}' records the metrics ({}), this dampbench computes ({}): it was written by "
                                 "another build",
                                 path, metrics, metric_list()));
  return store;
}

RunRecord run_record(int index, const RunResult& run) {
  return {index, run.best_value, run.best_metrics, run.best_params, run.evaluations, run.stop_reason,
          improvement_points(run), run.at_local_optimum};
}

StoreLock::StoreLock(const std::string& store_path) {
  const std::string lock_path = store_path + ".lock";
  std::error_code ec;
  if (const auto dir = std::filesystem::path(store_path).parent_path(); !dir.empty()) {
    std::filesystem::create_directories(dir, ec);
    if (ec) throw StoreError(fmt::format("cannot create the folder '{}' of store '{}': {}", dir.string(), store_path, ec.message()));
  }
  fd_ = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw StoreError(fmt::format("cannot create the lock file '{}' of store '{}': {}", lock_path, store_path, std::strerror(errno)));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK)
      throw StoreError(fmt::format("store '{}' is in use by another dampbench run (it holds '{}'): wait for it to "
                                   "finish, or give this run another --store",
                                   store_path, lock_path));
    throw StoreError(fmt::format("cannot lock store '{}' ({}): {}", store_path, lock_path, std::strerror(error)));
  }
}

StoreLock::~StoreLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the flock
}

Store Store::create_or_resume(const std::string& path, const StoreHeader& h) {
  std::error_code ec;
  bool exists = std::filesystem::exists(path, ec);
  if (exists && is_empty_database(path)) {
    // A store whose creation was killed before its first commit: start it again.
    std::filesystem::remove(path, ec);
    std::filesystem::remove(path + "-wal", ec);
    std::filesystem::remove(path + "-shm", ec);
    exists = false;
  }
  if (!exists) {
    if (const auto dir = std::filesystem::path(path).parent_path(); !dir.empty()) std::filesystem::create_directories(dir, ec);
    Store store(open_db(path, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE), path);
    store.exec("PRAGMA journal_mode=WAL");
    store.exec("PRAGMA synchronous=NORMAL");
    store.exec("BEGIN");
    store.exec(kSchema);
    store.exec(fmt::format("PRAGMA user_version={}", kStoreFormat).c_str());
    {
      Stmt s(store.db_, "INSERT INTO meta(key, value) VALUES(?, ?)");
      for (const auto& [k, v] : std::vector<std::pair<std::string, std::string>>{
               {"format", std::to_string(kStoreFormat)}, {"name", h.name}, {"spec_hash", h.spec_hash},
               {"spec_path", h.spec_path}, {"dampbench_version", h.dampbench_version}, {"build_flags", h.build_flags},
               {"groups", std::to_string(h.groups)}, {"tasks", std::to_string(h.tasks)}, {"metrics", metric_list()},
               {"created", now_utc()}})
        s.bind(1, k).bind(2, v).run();
      if (!h.shard.empty()) s.bind(1, std::string("shard")).bind(2, h.shard).run();
    }
    {
      Stmt s(store.db_, "INSERT INTO parts VALUES(?, ?, ?, ?, ?, ?, ?)");
      for (int p = 0; p < static_cast<int>(h.parts.size()); ++p) {
        const auto& x = h.parts[p];
        s.bind(1, p).bind(2, x.name).bind(3, x.title).bind(4, x.path).bind(5, x.source)
            .bind(6, static_cast<long long>(x.seed)).bind(7, x.runs).run();
      }
    }
    {
      Stmt s(store.db_, "INSERT INTO models VALUES(?, ?, ?, ?, ?, ?, ?, ?)");
      std::map<int, int> n;
      for (const auto& m : h.models)
        s.bind(1, m.part).bind(2, n[m.part]++).bind(3, m.name).bind(4, m.model_id).bind(5, m.fixture).bind(6, m.laws)
            .bind(7, m.bounds).bind(8, json(m.params).dump()).run();
    }
    {
      Stmt s(store.db_, "INSERT INTO optimizers VALUES(?, ?, ?, ?, ?, ?, ?)");
      std::map<int, int> n;
      for (const auto& o : h.optimizers)
        s.bind(1, o.part).bind(2, n[o.part]++).bind(3, o.label).bind(4, o.name).bind(5, o.population)
            .bind(6, o.iterations).bind(7, json(o.settings).dump()).run();
    }
    {
      Stmt s(store.db_, "INSERT INTO splits VALUES(?, ?, ?)");
      std::map<int, int> n;
      for (const auto& [part, name] : h.splits) s.bind(1, part).bind(2, n[part]++).bind(3, name).run();
    }
    {
      Stmt s(store.db_, "INSERT INTO datasets VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
      std::map<int, int> n;
      for (const auto& d : h.datasets) {
        json vars = json::object();
        for (const auto& [k, v] : d.variables) vars[k] = v;
        s.bind(1, d.part).bind(2, n[d.part]++).bind(3, d.name).bind(4, d.collection).bind(5, d.label).bind(6, d.path)
            .bind(7, d.samples).bind(8, d.hash).bind(9, vars.dump(-1, ' ', false, json::error_handler_t::replace))
            .bind(10, d.error).run();
      }
    }
    {
      Stmt s(store.db_, "INSERT INTO fitsets VALUES(?, ?, ?, ?, ?, ?)");
      std::map<std::pair<int, int>, int> n;
      for (const auto& f : h.fitsets)
        s.bind(1, f.part).bind(2, f.split).bind(3, n[{f.part, f.split}]++).bind(4, f.label).bind(5, json(f.fit).dump())
            .bind(6, json(f.predict).dump()).run();
    }
    store.exec("COMMIT");
    return store;
  }

  Store store = open(path);
  const std::string version = store.meta("dampbench_version"), flags = store.meta("build_flags");
  if (version != h.dampbench_version || flags != h.build_flags)
    throw StoreError(fmt::format(
        "store '{}' was written by dampbench {} ({}), this is dampbench {} ({}): its results would not be "
        "bit-identical; {}give another --store or --fresh to start over",
        path, version, flags, h.dampbench_version, h.build_flags,
        version == h.dampbench_version && differ_only_in_isa(flags, h.build_flags)
            ? fmt::format("resume it with the vector level it was written with (--isa {}, if this CPU has it), or ",
                          isa_of_build_flags(flags))
            : ""));
  if (const std::string hash = store.meta("spec_hash"); hash != h.spec_hash)
    throw StoreError(fmt::format(
        "store '{}' belongs to another sweep spec ('{}' from {}, spec hash {}; this spec '{}' has hash {}): give "
        "another --store, or --fresh to start over",
        path, store.meta("name"), store.meta("spec_path"), hash, h.name, h.spec_hash));
  if (const std::string shard = store.meta("shard"); shard != h.shard)
    throw StoreError(fmt::format("store '{}' holds {}, this run {}: give the store of this shard with --store",
                                 path, shard.empty() ? "the whole sweep" : "shard " + shard,
                                 h.shard.empty() ? "the whole sweep" : "shard " + h.shard));
  const StoreHeader stored = store.header();
  if (stored.datasets.size() != h.datasets.size())
    throw StoreError(fmt::format("store '{}' was written for {} datasets, the sweep now has {} (a glob matches other "
                                 "files?): give another --store, or --fresh to start over",
                                 path, stored.datasets.size(), h.datasets.size()));
  for (std::size_t i = 0; i < h.datasets.size(); ++i) {
    const auto &a = stored.datasets[i], &b = h.datasets[i];
    if (a.name != b.name || a.hash != b.hash || a.part != b.part)
      throw StoreError(fmt::format("store '{}': dataset '{}' ({}) changed since the store was written (hash {}, now "
                                   "'{}' hash {}): give another --store, or --fresh to start over",
                                   path, a.name, a.path, a.hash, b.name, b.hash));
  }
  // Titles, labels and the tables asked for may change without touching results: keep the latest.
  store.exec("BEGIN");
  {
    Stmt s(store.db_, "UPDATE parts SET title=?, path=?, source=? WHERE part=?");
    for (int p = 0; p < static_cast<int>(h.parts.size()); ++p)
      s.bind(1, h.parts[p].title).bind(2, h.parts[p].path).bind(3, h.parts[p].source).bind(4, p).run();
    Stmt m(store.db_, "UPDATE meta SET value=? WHERE key='spec_path'");
    m.bind(1, h.spec_path).run();
  }
  store.exec("COMMIT");
  return store;
}

StoreHeader Store::header() const {
  StoreHeader h;
  h.name = meta("name");
  h.spec_hash = meta("spec_hash");
  h.spec_path = meta("spec_path");
  h.dampbench_version = meta("dampbench_version");
  h.build_flags = meta("build_flags");
  h.shard = meta("shard");
  h.groups = count(meta("groups"));
  h.tasks = count(meta("tasks"));
  {
    Stmt s(db_, "SELECT name, title, path, source, seed, runs FROM parts ORDER BY part");
    while (s.step())
      h.parts.push_back({s.text(0), s.text(1), s.text(2), s.text(3), static_cast<std::uint64_t>(s.integer(4)),
                         static_cast<int>(s.integer(5))});
  }
  {
    Stmt s(db_, "SELECT part, name, model_id, fixture, laws, bounds, params FROM models ORDER BY part, model");
    while (s.step())
      h.models.push_back({static_cast<int>(s.integer(0)), s.text(1), s.text(2), s.text(3), s.text(4), s.text(5),
                          json::parse(s.text(6)).get<std::vector<std::string>>()});
  }
  {
    Stmt s(db_, "SELECT part, label, name, population, iterations, settings FROM optimizers ORDER BY part, optimizer");
    while (s.step())
      h.optimizers.push_back({static_cast<int>(s.integer(0)), s.text(1), s.text(2), static_cast<int>(s.integer(3)),
                              static_cast<int>(s.integer(4)),
                              json::parse(s.text(5)).get<std::map<std::string, std::string>>()});
  }
  {
    Stmt s(db_, "SELECT part, name FROM splits ORDER BY part, split");
    while (s.step()) h.splits.emplace_back(static_cast<int>(s.integer(0)), s.text(1));
  }
  {
    Stmt s(db_, "SELECT part, name, collection, label, path, hash, error, samples, variables FROM datasets "
                "ORDER BY part, dataset");
    while (s.step()) {
      StoreDataset d{static_cast<int>(s.integer(0)), s.text(1), s.text(2), s.text(3), s.text(4), s.text(5), s.text(6),
                     s.integer(7), {}};
      const json vars = json::parse(s.text(8));
      for (const auto& [k, v] : vars.items())
        if (v.is_number()) d.variables[k] = v.get<double>();
      h.datasets.push_back(std::move(d));
    }
  }
  {
    Stmt s(db_, "SELECT part, split, label, fit, predict FROM fitsets ORDER BY part, split, fitset");
    while (s.step())
      h.fitsets.push_back({static_cast<int>(s.integer(0)), static_cast<int>(s.integer(1)), s.text(2),
                           json::parse(s.text(3)).get<std::vector<int>>(), json::parse(s.text(4)).get<std::vector<int>>()});
  }
  return h;
}

void Store::write(const GroupRecord& g) {
  exec("BEGIN IMMEDIATE");
  try {
    for (const char* table : {"runs", "dataset_metrics", "sensitivity", "identifiability", "groups"}) {
      Stmt del(db_, fmt::format("DELETE FROM {} WHERE grp=?", table).c_str());
      del.bind(1, g.index).run();
    }
    Stmt s(db_, "INSERT INTO groups VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
    s.bind(1, g.index).bind(2, g.part).bind(3, g.split).bind(4, g.fitset).bind(5, g.model).bind(6, g.optimizer)
        .bind(7, std::string(metric_name(g.metric))).bind(8, g.runs).bind(9, fmt::format("{:016x}", g.task_key))
        .bind(10, std::string(g.failed ? "failed" : "done")).bind(11, g.message).bind(12, g.wall_time_s)
        .bind(13, g.candidate_samples).bind(14, g.evaluations).bind(15, g.dampbench_version).bind(16, g.build_flags)
        .bind(17, g.spec_hash).bind(18, g.dataset_hash).bind(19, g.finished_at.empty() ? now_utc() : g.finished_at).run();
    Stmt r(db_, "INSERT INTO runs VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?)");
    for (const auto& x : g.run_results)
      r.bind(1, g.index).bind(2, x.run).bind(3, x.best_value).bind(4, x.metrics).bind(5, x.params)
          .bind(6, x.evaluations).bind(7, x.stop_reason).bind(8, trace_blob(x.trace)).bind(9, x.at_local_optimum ? 1 : 0).run();
    Stmt d(db_, "INSERT INTO dataset_metrics VALUES(?, ?, ?, ?, ?)");
    for (const auto& x : g.dataset_metrics)
      d.bind(1, g.index).bind(2, x.run).bind(3, x.dataset).bind(4, std::string(x.predicted ? "predict" : "fit"))
          .bind(5, x.metrics).run();
    if (g.sensitivity) {
      Stmt t(db_, "INSERT INTO sensitivity VALUES(?, ?, ?, ?)");
      t.bind(1, g.index).bind(2, g.sensitivity->dataset).bind(3, g.sensitivity->S).bind(4, g.sensitivity->SP).run();
    }
    if (g.identifiability) {
      const Identifiability& id = *g.identifiability;
      std::vector<double> correlation;
      for (const auto& row : id.correlation) correlation.insert(correlation.end(), row.begin(), row.end());
      Stmt t(db_, "INSERT INTO identifiability VALUES(?, ?, ?, ?, ?, ?)");
      t.bind(1, g.index).bind(2, id.samples).bind(3, id.std_error).bind(4, id.relative_error).bind(5, correlation)
          .bind(6, json(id.flags).dump()).run();
    }
    exec("COMMIT");
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

std::vector<char> Store::finished() const {
  std::vector<char> done(static_cast<std::size_t>(count(meta("groups"))), 0);
  Stmt s(db_, "SELECT grp FROM groups");
  while (s.step()) {
    const long long i = s.integer(0);
    if (i >= 0 && i < static_cast<long long>(done.size())) done[static_cast<std::size_t>(i)] = 1;
  }
  return done;
}

long long Store::stored_groups() const {
  Stmt s(db_, "SELECT COUNT(*) FROM groups");
  s.step();
  return s.integer(0);
}

namespace {

constexpr const char* kGroupColumns =
    "grp, part, split, fitset, model, optimizer, metric, runs, task_key, status, message, wall_time_s, "
    "candidate_samples, evaluations, dampbench_version, build_flags, spec_hash, dataset_hash, finished_at";

GroupRecord read_group_row(const Stmt& s) {
  GroupRecord g;
  g.index = s.integer(0);
  g.part = static_cast<int>(s.integer(1));
  g.split = static_cast<int>(s.integer(2));
  g.fitset = static_cast<int>(s.integer(3));
  g.model = static_cast<int>(s.integer(4));
  g.optimizer = static_cast<int>(s.integer(5));
  g.metric = parse_metric(s.text(6));
  g.runs = static_cast<int>(s.integer(7));
  g.task_key = std::stoull(s.text(8), nullptr, 16);
  g.failed = s.text(9) == "failed";
  g.message = s.text(10);
  g.wall_time_s = s.real(11);
  g.candidate_samples = s.real(12);
  g.evaluations = s.integer(13);
  g.dampbench_version = s.text(14);
  g.build_flags = s.text(15);
  g.spec_hash = s.text(16);
  g.dataset_hash = s.text(17);
  g.finished_at = s.text(18);
  return g;
}

/// Run results, per-dataset metrics and sensitivity of the groups `where` selects ("grp=?" bound to `grp`,
/// or "" for every group), each row attached through `slot` (group number → record, nullptr to skip).
template <class Slot>
void read_details(sqlite3* db, const std::string& where, long long grp, bool runs, bool traces, bool details, Slot&& slot) {
  auto prepare = [&](const std::string& sql) {
    auto s = std::make_unique<Stmt>(db, sql.c_str());
    if (!where.empty()) s->bind(1, grp);
    return s;
  };
  const std::string filter = where.empty() ? "" : " WHERE " + where;
  if (runs) {
    const auto r = prepare(fmt::format("SELECT grp, run, best_value, metrics, params, evaluations, stop_reason, local_optimum{} "
                                       "FROM runs{} ORDER BY grp, run",
                                       traces ? ", trace" : "", filter));
    while (r->step()) {
      GroupRecord* g = slot(r->integer(0));
      if (!g) continue;
      RunRecord x;
      x.run = static_cast<int>(r->integer(1));
      x.best_value = r->real(2);
      x.metrics = r->metric_row(3);
      x.params = r->doubles(4);
      x.evaluations = r->integer(5);
      x.stop_reason = r->text(6);
      x.at_local_optimum = r->integer(7) != 0;
      if (traces) x.trace = trace_points(r->doubles(8));
      g->run_results.push_back(std::move(x));
    }
  }
  if (details) {
    const auto d = prepare("SELECT grp, run, dataset, role, metrics FROM dataset_metrics" + filter + " ORDER BY grp, run, dataset");
    while (d->step())
      if (GroupRecord* g = slot(d->integer(0)))
        g->dataset_metrics.push_back({static_cast<int>(d->integer(1)), static_cast<int>(d->integer(2)),
                                      d->text(3) == "predict", d->metric_row(4)});
    const auto t = prepare("SELECT grp, dataset, S, SP FROM sensitivity" + filter);
    while (t->step())
      if (GroupRecord* g = slot(t->integer(0)))
        g->sensitivity = SensitivityRecord{static_cast<int>(t->integer(1)), t->doubles(2), t->doubles(3)};
    const auto i = prepare("SELECT grp, samples, std_error, relative_error, correlation, flags FROM identifiability" + filter);
    while (i->step())
      if (GroupRecord* g = slot(i->integer(0))) {
        Identifiability id;
        id.samples = static_cast<int>(i->integer(1));
        id.std_error = i->doubles(2);
        id.relative_error = i->doubles(3);
        const std::vector<double> correlation = i->doubles(4);
        const std::size_t p = id.std_error.size();
        for (std::size_t r = 0; r < p && (r + 1) * p <= correlation.size(); ++r)
          id.correlation.emplace_back(correlation.begin() + static_cast<std::ptrdiff_t>(r * p),
                                      correlation.begin() + static_cast<std::ptrdiff_t>((r + 1) * p));
        id.flags = json::parse(i->text(5)).template get<std::vector<std::vector<std::string>>>();
        g->identifiability = std::move(id);
      }
  }
}

}  // namespace

std::vector<GroupRecord> Store::groups(const GroupQuery& q) const {
  std::vector<GroupRecord> out;
  Stmt s(db_, fmt::format("SELECT {} FROM groups {} ORDER BY grp", kGroupColumns, q.part >= 0 ? "WHERE part=?" : "").c_str());
  if (q.part >= 0) s.bind(1, q.part);
  while (s.step()) out.push_back(read_group_row(s));
  // One pass over each table in group order, not one query per group: a store may hold 10^5 groups.
  std::map<long long, std::size_t> index;
  for (std::size_t i = 0; i < out.size(); ++i) index[out[i].index] = i;
  read_details(db_, "", 0, q.runs, q.traces, q.details, [&](long long grp) -> GroupRecord* {
    const auto it = index.find(grp);
    return it == index.end() ? nullptr : &out[it->second];
  });
  return out;
}

std::optional<GroupRecord> Store::group(long long index, bool traces) const {
  Stmt s(db_, fmt::format("SELECT {} FROM groups WHERE grp=?", kGroupColumns).c_str());
  s.bind(1, index);
  if (!s.step()) return std::nullopt;
  GroupRecord g = read_group_row(s);
  read_details(db_, "grp=?", index, true, traces, true, [&](long long) { return &g; });
  return g;
}

namespace {

std::string bits(double v) { return fmt::format("0x{:016x} ({:.17g})", std::bit_cast<std::uint64_t>(v), v); }
bool same(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

}  // namespace

void sort_dataset_metrics(std::vector<DatasetMetricRecord>& metrics) {
  std::stable_sort(metrics.begin(), metrics.end(), [](const DatasetMetricRecord& x, const DatasetMetricRecord& y) {
    return std::pair(x.run, x.dataset) < std::pair(y.run, y.dataset);
  });
}

std::vector<std::string> compare_records(const GroupRecord& stored, const GroupRecord& recomputed,
                                         const std::vector<std::string>& names) {
  // Per-dataset metrics compared in one order, whatever order each record lists them in.
  GroupRecord a = stored, b = recomputed;
  sort_dataset_metrics(a.dataset_metrics);
  sort_dataset_metrics(b.dataset_metrics);
  std::vector<std::string> diff;
  auto num = [&](const std::string& what, double x, double y) {
    if (!same(x, y)) diff.push_back(fmt::format("{}: stored {} vs recomputed {}", what, bits(x), bits(y)));
  };
  if (a.failed != b.failed)
    diff.push_back(fmt::format("status: stored {} vs recomputed {}", a.failed ? "failed" : "done", b.failed ? "failed" : "done"));
  if (a.message != b.message) diff.push_back(fmt::format("message: stored '{}' vs recomputed '{}'", a.message, b.message));
  if (a.task_key != b.task_key) diff.push_back("task key differs");
  if (a.evaluations != b.evaluations)
    diff.push_back(fmt::format("evaluations: stored {} vs recomputed {}", a.evaluations, b.evaluations));
  num("candidate_samples", a.candidate_samples, b.candidate_samples);
  if (a.run_results.size() != b.run_results.size()) {
    diff.push_back(fmt::format("runs: stored {} vs recomputed {}", a.run_results.size(), b.run_results.size()));
    return diff;
  }
  for (std::size_t r = 0; r < a.run_results.size(); ++r) {
    const auto &x = a.run_results[r], &y = b.run_results[r];
    const std::string run = fmt::format("run {}", x.run);
    num(run + " best_value", x.best_value, y.best_value);
    for (int m = 0; m < kMetricCount; ++m)
      num(fmt::format("{} metric {}", run, metric_name(kAllMetrics[m])), x.metrics[m], y.metrics[m]);
    if (x.params.size() != y.params.size()) diff.push_back(run + ": parameter count differs");
    for (std::size_t j = 0; j < std::min(x.params.size(), y.params.size()); ++j)
      num(fmt::format("{} params[{}]{}", run, j, j < names.size() ? " " + names[j] : ""), x.params[j], y.params[j]);
    if (x.evaluations != y.evaluations)
      diff.push_back(fmt::format("{} evaluations: stored {} vs recomputed {}", run, x.evaluations, y.evaluations));
    if (x.stop_reason != y.stop_reason) diff.push_back(fmt::format("{} stop reason: {} vs {}", run, x.stop_reason, y.stop_reason));
    if (x.at_local_optimum != y.at_local_optimum) diff.push_back(fmt::format("{} local optimum: {} vs {}", run, x.at_local_optimum, y.at_local_optimum));
    if (x.trace.size() != y.trace.size()) {
      diff.push_back(fmt::format("{} trace: stored {} points vs recomputed {}", run, x.trace.size(), y.trace.size()));
    } else {
      for (std::size_t k = 0; k < x.trace.size(); ++k) {
        if (x.trace[k].evaluations != y.trace[k].evaluations) diff.push_back(fmt::format("{} trace[{}] evaluations differ", run, k));
        num(fmt::format("{} trace[{}]", run, k), x.trace[k].value, y.trace[k].value);
      }
    }
  }
  if (a.dataset_metrics.size() != b.dataset_metrics.size()) {
    diff.push_back("per-dataset metrics: count differs");
  } else {
    for (std::size_t i = 0; i < a.dataset_metrics.size(); ++i) {
      if (a.dataset_metrics[i].dataset != b.dataset_metrics[i].dataset || a.dataset_metrics[i].predicted != b.dataset_metrics[i].predicted)
        diff.push_back(fmt::format("run {}: per-dataset metrics of other datasets or roles", a.dataset_metrics[i].run));
      for (int m = 0; m < kMetricCount; ++m)
        num(fmt::format("run {} dataset {} metric {}", a.dataset_metrics[i].run, a.dataset_metrics[i].dataset,
                        metric_name(kAllMetrics[m])),
            a.dataset_metrics[i].metrics[m], b.dataset_metrics[i].metrics[m]);
    }
  }
  if (a.sensitivity.has_value() != b.sensitivity.has_value()) {
    diff.push_back("sensitivity: present in one only");
  } else if (a.sensitivity) {
    const auto &x = *a.sensitivity, &y = *b.sensitivity;
    if (x.S.size() != y.S.size() || x.SP.size() != y.SP.size()) diff.push_back("sensitivity: size differs");
    else
      for (std::size_t j = 0; j < x.S.size(); ++j) {
        num(fmt::format("sensitivity S[{}]", j), x.S[j], y.S[j]);
        num(fmt::format("sensitivity SP[{}]", j), x.SP[j], y.SP[j]);
      }
  }
  if (a.identifiability.has_value() != b.identifiability.has_value()) {
    diff.push_back("identifiability: present in one only");
  } else if (a.identifiability) {
    const auto &x = *a.identifiability, &y = *b.identifiability;
    if (x.std_error.size() != y.std_error.size() || x.correlation.size() != y.correlation.size()) {
      diff.push_back("identifiability: size differs");
    } else {
      for (std::size_t j = 0; j < x.std_error.size(); ++j) {
        const std::string name = j < names.size() ? " " + names[j] : "";
        num(fmt::format("identifiability std_error[{}]{}", j, name), x.std_error[j], y.std_error[j]);
        num(fmt::format("identifiability relative_error[{}]{}", j, name), x.relative_error[j], y.relative_error[j]);
        for (std::size_t k = 0; k < x.correlation[j].size() && k < y.correlation[j].size(); ++k)
          num(fmt::format("identifiability correlation[{}][{}]", j, k), x.correlation[j][k], y.correlation[j][k]);
      }
      if (x.flags != y.flags) diff.push_back("identifiability: flags differ");
    }
  }
  return diff;
}

}  // namespace dampbench::sweep
