#pragma once
// A sweep made concrete: datasets loaded, models and optimizers built, and every task group numbered.
//
// A task is one identification run; a task group is every run of one (model, fit datasets, optimizer,
// metric) — one call of identify(), whose runs advance in lockstep as one batch. Groups are numbered
// 0 … groups()−1 in a fixed order (part, split, fit set, model × optimizer, metric) and decoded on demand
// from their number, so a sweep of 10⁵ tasks is never held in memory as a list.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/record/dataset.hpp"
#include "engine/record/signals.hpp"
#include "engine/sweep/spec.hpp"
#include "engine/sweep/store.hpp"

namespace dampbench::sweep {

/// Reads one record with the loader options of a dataset entry (the command line passes its load_data).
using Loader = std::function<Dataset(const RecordOptions&)>;

struct LoadedDataset {
  Signals signals;    ///< empty when loading failed
  std::string error;  ///< the loader's message when it failed
  std::string hash;   ///< dataset_hash(signals), or a hash of the error text
  [[nodiscard]] bool ok() const { return error.empty(); }
};

/// Reads and prepares one dataset of a sweep file; a failure is kept in `error` (never throws).
LoadedDataset load_dataset(const DatasetSpec& d, const Loader& loader);

/// Datasets fitted together (one identification) and the datasets their result predicts.
struct FitSet {
  std::vector<int> fit, predict;  ///< dataset indices in the part
  std::string label;              ///< table label: the dataset's name, "I=0.5", or the split name
  std::string key_name;           ///< fit dataset names joined by '+' (enters the task key)
};

struct SplitPlan {
  std::vector<FitSet> fitsets;
  std::vector<std::pair<int, int>> pairs;  ///< (model, optimizer) indices identified in this split
  long long groups = 0;
  long long tasks = 0;
};

struct PartPlan {
  const PartSpec* spec = nullptr;
  std::vector<ResolvedModel> models;
  std::vector<OptimizerFactory> factories;
  std::vector<LoadedDataset> datasets;
  std::vector<SplitPlan> splits;
  bool holds_any = false;  ///< some model holds to another's fit (ModelSpec::hold): groups keep their best runs
};

class Plan {
 public:
  /// Loads every dataset (in parallel) and numbers the groups. Loading failures are kept: the groups that
  /// need the dataset fail with its message. InputError when a split selects no dataset.
  Plan(SweepSpec spec, const Loader& loader);
  Plan(const Plan&) = delete;  // parts point into spec_
  Plan& operator=(const Plan&) = delete;
  Plan(Plan&&) = default;

  [[nodiscard]] const SweepSpec& spec() const { return spec_; }
  [[nodiscard]] const std::vector<PartPlan>& parts() const { return parts_; }
  [[nodiscard]] long long groups() const { return groups_; }
  [[nodiscard]] long long tasks() const { return tasks_; }
  [[nodiscard]] GroupRef group(long long index) const;
  /// The number of the group of (part, split, fit set, model, optimizer, metric); −1 when the split does not
  /// identify that model with that optimizer, or the part has no such metric.
  [[nodiscard]] long long group_index(int part, int split, int fitset, int model, int optimizer, Metric metric) const;

  /// Hashes of the datasets a group uses (fit then predict), combined.
  [[nodiscard]] std::string group_dataset_hash(const GroupRef& g) const;
  /// "model on fit set, optimizer, metric" for messages.
  [[nodiscard]] std::string describe(const GroupRef& g) const;

 private:
  SweepSpec spec_;
  std::vector<PartPlan> parts_;
  struct Block {
    long long first;
    int part, split;
  };
  std::vector<Block> blocks_;
  long long groups_ = 0, tasks_ = 0;
};

}  // namespace dampbench::sweep
