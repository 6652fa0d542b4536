// The store's life: creating it or resuming it for the same sweep, opening it to read, writing one group per
// transaction. The header, the reads, the lock and verify's comparison live in store/.
#include "engine/sweep/store.hpp"

#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <sqlite3.h>

#include "engine/common/error.hpp"
#include "engine/sweep/fingerprint.hpp"
#include "engine/sweep/store/schema.hpp"
#include "engine/sweep/store/sqlite_access.hpp"

namespace dampbench::sweep {

using json = nlohmann::json;
using namespace store_db;

int GroupRecord::best_run() const {
  int best = run_results.empty() ? -1 : 0;
  for (int r = 1; r < static_cast<int>(run_results.size()); ++r)
    if (run_results[r].best_value < run_results[best].best_value) best = r;
  return best;
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
  if (version == 2) {  // format 3 added groups.laws: a format-2 store's groups chose no laws
    store.exec("BEGIN IMMEDIATE");
    store.exec("ALTER TABLE groups ADD COLUMN laws TEXT NOT NULL DEFAULT ''");
    store.exec(fmt::format("UPDATE meta SET value='{}' WHERE key='format'", kStoreFormat).c_str());
    store.exec(fmt::format("PRAGMA user_version={}", kStoreFormat).c_str());
    store.exec("COMMIT");
    version = kStoreFormat;
  }
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

Store Store::create(const std::string& path, const StoreHeader& h) {
  std::error_code ec;
  if (const auto dir = std::filesystem::path(path).parent_path(); !dir.empty()) std::filesystem::create_directories(dir, ec);
  Store store(open_db(path, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE), path);
  store.exec("PRAGMA journal_mode=WAL");
  store.exec("PRAGMA synchronous=NORMAL");
  store.exec("BEGIN");
  store.exec(kSchema);
  store.exec(fmt::format("PRAGMA user_version={}", kStoreFormat).c_str());
  insert_header(store.db_, h);
  store.exec("COMMIT");
  return store;
}

void Store::check_same_sweep(const StoreHeader& h) const {
  const std::string version = meta("dampbench_version"), flags = meta("build_flags");
  if (version != h.dampbench_version || flags != h.build_flags)
    throw StoreError(fmt::format(
        "store '{}' was written by dampbench {} ({}), this is dampbench {} ({}): its results would not be "
        "bit-identical; {}give another --store or --fresh to start over",
        path_, version, flags, h.dampbench_version, h.build_flags,
        version == h.dampbench_version && differ_only_in_isa(flags, h.build_flags)
            ? fmt::format("resume it with the vector level it was written with (--isa {}, if this CPU has it), or ",
                          isa_of_build_flags(flags))
            : ""));
  if (const std::string hash = meta("spec_hash"); hash != h.spec_hash)
    throw StoreError(fmt::format(
        "store '{}' belongs to another sweep spec ('{}' from {}, spec hash {}; this spec '{}' has hash {}): give "
        "another --store, or --fresh to start over",
        path_, meta("name"), meta("spec_path"), hash, h.name, h.spec_hash));
  if (const std::string shard = meta("shard"); shard != h.shard)
    throw StoreError(fmt::format("store '{}' holds {}, this run {}: give the store of this shard with --store",
                                 path_, shard.empty() ? "the whole sweep" : "shard " + shard,
                                 h.shard.empty() ? "the whole sweep" : "shard " + h.shard));
  const StoreHeader stored = header();
  if (stored.datasets.size() != h.datasets.size())
    throw StoreError(fmt::format("store '{}' was written for {} datasets, the sweep now has {} (a glob matches other "
                                 "files?): give another --store, or --fresh to start over",
                                 path_, stored.datasets.size(), h.datasets.size()));
  for (std::size_t i = 0; i < h.datasets.size(); ++i) {
    const auto &a = stored.datasets[i], &b = h.datasets[i];
    if (a.name != b.name || a.hash != b.hash || a.part != b.part)
      throw StoreError(fmt::format("store '{}': dataset '{}' ({}) changed since the store was written (hash {}, now "
                                   "'{}' hash {}): give another --store, or --fresh to start over",
                                   path_, a.name, a.path, a.hash, b.name, b.hash));
  }
}

void Store::update_labels(const StoreHeader& h) {
  // Titles, labels and the tables asked for may change without touching results: keep the latest.
  exec("BEGIN");
  {
    Stmt s(db_, "UPDATE parts SET title=?, path=?, source=? WHERE part=?");
    for (int p = 0; p < static_cast<int>(h.parts.size()); ++p)
      s.bind(1, h.parts[p].title).bind(2, h.parts[p].path).bind(3, h.parts[p].source).bind(4, p).run();
    Stmt m(db_, "UPDATE meta SET value=? WHERE key='spec_path'");
    m.bind(1, h.spec_path).run();
  }
  exec("COMMIT");
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
  if (!exists) return create(path, h);
  Store store = open(path);
  store.check_same_sweep(h);
  store.update_labels(h);
  return store;
}

void Store::write(const GroupRecord& g) {
  exec("BEGIN IMMEDIATE");
  try {
    for (const char* table : {"runs", "dataset_metrics", "sensitivity", "identifiability", "groups"}) {
      Stmt del(db_, fmt::format("DELETE FROM {} WHERE grp=?", table).c_str());
      del.bind(1, g.index).run();
    }
    Stmt s(db_, "INSERT INTO groups VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
    s.bind(1, g.index).bind(2, g.part).bind(3, g.split).bind(4, g.fitset).bind(5, g.model).bind(6, g.optimizer)
        .bind(7, std::string(metric_name(g.metric))).bind(8, g.runs).bind(9, fmt::format("{:016x}", g.task_key))
        .bind(10, std::string(g.failed ? "failed" : "done")).bind(11, g.message).bind(12, g.wall_time_s)
        .bind(13, g.candidate_samples).bind(14, g.evaluations).bind(15, g.dampbench_version).bind(16, g.build_flags)
        .bind(17, g.spec_hash).bind(18, g.dataset_hash).bind(19, g.finished_at.empty() ? now_utc() : g.finished_at)
        .bind(20, g.laws).run();
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
  std::vector<char> done(static_cast<std::size_t>(count(meta("groups"), "meta groups")), 0);
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

}  // namespace dampbench::sweep
