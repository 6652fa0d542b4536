#pragma once
// The results store of a sweep: one SQLite file (WAL mode). Every finished task group is written in one
// transaction, so a killed sweep loses at most the groups in flight and the file stays valid; running the
// same sweep on the store again skips what it holds.
//
// Doubles that results are compared on (best values, metrics, parameters, traces) are stored as their
// 8 bytes (little-endian blobs) or as SQLite REAL, which keeps all 64 bits; reading them back gives the same
// bits. A store belongs to one sweep spec (its hash), one dampbench version and build flags, and one set of
// datasets (names and hashes): anything else is refused with a message saying what differs.
//
// Tables (schema version kStoreFormat):
//   meta(key, value)                       format, dampbench_version, build_flags, spec_hash, spec_path, name,
//                                          shard ("i/n" for a shard's store, absent otherwise), ...
//   parts, models, optimizers, splits, datasets, fitsets   the plan, for tables and verify
//   groups(grp, part, split, fitset, model, optimizer, metric, runs, task_key, status, message, wall_time_s,
//          candidate_samples, evaluations, dampbench_version, build_flags, spec_hash, dataset_hash, finished_at,
//          laws)                           laws: what a group of a laws = "auto" model chose (else empty)
//   runs(grp, run, best_value, metrics, params, evaluations, stop_reason, trace, local_optimum)
//   dataset_metrics(grp, run, dataset, role, metrics)   per-dataset metrics of joint fits and predictions
//   sensitivity(grp, dataset, S, SP)
//   identifiability(grp, samples, std_error, relative_error, correlation, flags)   at the best run's parameters
//                                          over the fit datasets (engine/identification/identifiability.hpp);
//                                          correlation row-major p × p, flags JSON [[flag, ...] per parameter]
#include <optional>
#include <string>
#include <vector>

#include "engine/sweep/store/lock.hpp"
#include "engine/sweep/store/records.hpp"
#include "engine/sweep/store/verify_diff.hpp"

struct sqlite3;

namespace dampbench::sweep {

class Store {
 public:
  /// Creates the store, or opens an existing one to resume after checking that it belongs to this sweep
  /// (format, dampbench version and build flags, spec hash, datasets); InputError says what differs.
  static Store create_or_resume(const std::string& path, const StoreHeader& header);
  /// Opens an existing store to read (InputError for a missing file, not a store, or another format).
  static Store open(const std::string& path);

  Store(Store&& other) noexcept;
  Store& operator=(Store&& other) noexcept;
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;
  ~Store();

  /// Writes one group in one transaction (replacing a stored group of the same number).
  void write(const GroupRecord& group);

  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] StoreHeader header() const;
  [[nodiscard]] std::string meta(const std::string& key) const;
  /// finished[i] != 0 for every stored group i (failed ones included); size = header groups.
  [[nodiscard]] std::vector<char> finished() const;
  [[nodiscard]] long long stored_groups() const;
  [[nodiscard]] std::vector<GroupRecord> groups(const GroupQuery& query = {}) const;
  [[nodiscard]] std::optional<GroupRecord> group(long long index, bool traces = true) const;

 private:
  Store(sqlite3* db, std::string path) : db_(db), path_(std::move(path)) {}
  /// A new store file with the schema and the header, in one transaction.
  static Store create(const std::string& path, const StoreHeader& header);
  /// Refuses (StoreError) a store written by another build, for another spec, shard or other datasets.
  void check_same_sweep(const StoreHeader& header) const;
  /// Keeps the latest titles, paths and spec text: they may change without touching results.
  void update_labels(const StoreHeader& header);
  void exec(const char* sql) const;
  sqlite3* db_ = nullptr;
  std::string path_;
};

}  // namespace dampbench::sweep
