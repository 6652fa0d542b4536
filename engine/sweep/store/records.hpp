#pragma once
// What a store holds, as C++ values: the plan it was written for (StoreHeader) and one record per finished task
// group (GroupRecord), written and read back bit for bit (engine/sweep/store.hpp).
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/identification/convergence.hpp"
#include "engine/identification/identifiability.hpp"
#include "engine/identification/identification.hpp"
#include "engine/model/metrics.hpp"

namespace dampbench::sweep {

inline constexpr int kStoreFormat = 3;  ///< the schema's version (store.hpp): Store::open refuses another

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
  /// A failed group's error; a done group's automatic budget summary (AutoBudgetReport::summary), else empty.
  std::string message;
  double wall_time_s = 0, candidate_samples = 0;
  long long evaluations = 0;
  std::string dampbench_version, build_flags, spec_hash, dataset_hash;  ///< fingerprint
  /// UTC time the group was first stored (ISO 8601); empty in a new record: write() stamps it. A merge copies it,
  /// so a merged store says when each shard finished its groups.
  std::string finished_at;
  /// The laws a group of a `laws = "auto"` model chose (parse_laws text on the model's gauged base: the runs' params
  /// are that law model's coefficients), or those of a held model with the values it held (ModelSpec::hold); empty
  /// for every other group.
  std::string laws;
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

}  // namespace dampbench::sweep
