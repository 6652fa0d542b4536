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
//          candidate_samples, evaluations, dampbench_version, build_flags, spec_hash, dataset_hash, finished_at)
//   runs(grp, run, best_value, metrics, params, evaluations, stop_reason, trace, local_optimum)
//   dataset_metrics(grp, run, dataset, role, metrics)   per-dataset metrics of joint fits and predictions
//   sensitivity(grp, dataset, S, SP)
//   identifiability(grp, samples, std_error, relative_error, correlation, flags)   at the best run's parameters
//                                          over the fit datasets (engine/identification/identifiability.hpp);
//                                          correlation row-major p × p, flags JSON [[flag, ...] per parameter]
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/identification/convergence.hpp"
#include "engine/identification/identifiability.hpp"
#include "engine/model/metrics.hpp"

struct sqlite3;

namespace dampbench::sweep {

inline constexpr int kStoreFormat = 2;  ///< 2: identifiability table, runs.local_optimum

struct StorePart {
  std::string name, title, path, source;
  std::uint64_t seed = 0;
  int runs = 0;
};
struct StoreModel {
  int part = 0;
  std::string name, model_id, fixture, laws, bounds;
  std::vector<std::string> params;
};
struct StoreOptimizer {
  int part = 0;
  std::string label, name;
  int population = 0, iterations = 0;
  std::map<std::string, std::string> settings;
};
struct StoreDataset {
  int part = 0;
  std::string name, collection, label, path, hash, error;
  long long samples = 0;
  std::map<std::string, double> variables;  ///< law variables (operating + amp/freq estimates)
};
struct StoreFitSet {
  int part = 0, split = 0;
  std::string label;
  std::vector<int> fit, predict;
};

/// What a store describes besides results; per-part lists keep their part's order.
struct StoreHeader {
  std::string name, spec_hash, spec_path;
  std::string dampbench_version, build_flags;
  std::string shard;  ///< "i/n" for the store of one shard (run --shard), "" for the whole sweep
  long long groups = 0, tasks = 0;  ///< in the whole sweep
  std::vector<StorePart> parts;
  std::vector<StoreModel> models;
  std::vector<StoreOptimizer> optimizers;
  std::vector<std::pair<int, std::string>> splits;  ///< (part, name)
  std::vector<StoreDataset> datasets;
  std::vector<StoreFitSet> fitsets;

  /// Index into the flat lists of the i-th entry of a part (-1 if absent).
  [[nodiscard]] int model(int part, int i) const;
  [[nodiscard]] int optimizer(int part, int i) const;
  [[nodiscard]] int dataset(int part, int i) const;
  [[nodiscard]] int fitset(int part, int split, int i) const;
  [[nodiscard]] std::string split_name(int part, int i) const;
};

struct RunRecord {
  int run = 0;
  double best_value = 0;
  std::array<double, kMetricCount> metrics{};
  std::vector<double> params;
  long long evaluations = 0;
  std::string stop_reason;
  std::vector<TracePoint> trace;  ///< the points where the best-so-far improved, and the last one
  bool at_local_optimum = false;  ///< RunResult::at_local_optimum
};

/// Run `index` of an identification as the store keeps it (its best-so-far history reduced by improvement_points).
RunRecord run_record(int index, const RunResult& run);

struct DatasetMetricRecord {
  int run = 0, dataset = 0;
  bool predicted = false;  ///< a prediction (else a fit dataset of a joint fit)
  std::array<double, kMetricCount> metrics{};
};

struct SensitivityRecord {
  int dataset = 0;
  std::vector<double> S, SP;
};

/// One task group, decoded from its number (Plan::group): which part, split, fit set, model, optimizer.
struct GroupRef {
  long long index = 0;
  int part = 0, split = 0, fitset = 0, model = 0, optimizer = 0;
  Metric metric = Metric::of_abs;
  int runs = 0;
  std::uint64_t task_key = 0;  ///< runs are keyed (seed, task_key, run)
};

/// One finished task group, as written and as read back.
struct GroupRecord : GroupRef {
  bool failed = false;
  std::string message;
  double wall_time_s = 0, candidate_samples = 0;
  long long evaluations = 0;
  std::string dampbench_version, build_flags, spec_hash, dataset_hash;  ///< fingerprint
  /// UTC time the group was first stored (ISO 8601); empty in a new record: write() stamps it. A merge copies it,
  /// so a merged store says when each shard finished its groups.
  std::string finished_at;
  std::vector<RunRecord> run_results;
  std::vector<DatasetMetricRecord> dataset_metrics;
  std::optional<SensitivityRecord> sensitivity;
  std::optional<Identifiability> identifiability;  ///< at the best run (absent when every run failed)

  [[nodiscard]] int best_run() const;  ///< lowest best_value, first on ties (-1 without runs)
};

struct GroupQuery {
  int part = -1;           ///< -1: every part
  bool runs = true;        ///< read run results
  bool traces = false;     ///< with their traces
  bool details = true;     ///< dataset metrics, sensitivity and identifiability
};

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
  void exec(const char* sql) const;
  sqlite3* db_ = nullptr;
  std::string path_;
};

/// Exclusive use of a store by one `dampbench run`: an flock on "<store>.lock", released when the process ends
/// (even by SIGKILL), so a second run on the same store is refused at once instead of both writing it.
class StoreLock {
 public:
  /// Creates the store's folder if needed and takes the lock; StoreError naming the store when another process
  /// holds it or the lock file cannot be created.
  explicit StoreLock(const std::string& store_path);
  StoreLock(const StoreLock&) = delete;
  StoreLock& operator=(const StoreLock&) = delete;
  ~StoreLock();

 private:
  int fd_ = -1;
};

/// Orders per-dataset metrics by (run, dataset), the order the store reads them back in.
void sort_dataset_metrics(std::vector<DatasetMetricRecord>& metrics);

/// Bit-exact comparison of two records of the same group (everything but wall time and fingerprint);
/// each difference as a line "run 3 params[1]: stored 0x… (1.25) vs 0x… (1.2500000000000002)".
std::vector<std::string> compare_records(const GroupRecord& stored, const GroupRecord& recomputed,
                                         const std::vector<std::string>& param_names = {});

}  // namespace dampbench::sweep
