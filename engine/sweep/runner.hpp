#pragma once
// Running a sweep: every task group not yet in the store is identified and written to it.
//
// Scheduling: a oneTBB pipeline hands out group numbers largest first (schedule.hpp; skipping stored ones
// and those of other shards), runs up to
// 2 × threads groups at once (each group's batch is itself split across cores by identify()), and writes
// finished groups to the store one transaction each, in whatever order they finish. Only groups in flight
// are held in memory. A group's result depends only on its number and the plan, never on what ran beside
// it, so resumed sweeps are bit-identical to uninterrupted ones.
#include <atomic>
#include <chrono>
#include <optional>
#include <vector>
#include <functional>
#include <string>

#include "engine/fit/record_fit_cache.hpp"
#include "engine/sweep/held_fit.hpp"
#include "engine/sweep/plan.hpp"
#include "engine/sweep/progress.hpp"
#include "engine/sweep/schedule.hpp"
#include "engine/sweep/store.hpp"

namespace dampbench::sweep {

/// Identifies one group: the fit of engine/fit (run_fit, keyed by the group's task key), then what a sweep adds
/// to it (per-dataset metrics of joint fits and predictions, sensitivity). Never throws for bad data or a model
/// error: the record is marked failed with the message. Groups that fit records alone first (laws = "auto",
/// start = "per-file") share those fits through `record_fits` when given (engine/fit/record_fit_cache.hpp: the
/// same bits either way); groups that hold to other groups' fits (a model's `hold`) find them in `group_fits`, or
/// make them (engine/sweep/held_fit.hpp).
GroupRecord run_group(const Plan& plan, long long index, RecordFitCache* record_fits = nullptr,
                      GroupFitCache* group_fits = nullptr);

/// The store header (plan, datasets, fingerprint) of a plan.
StoreHeader make_store_header(const Plan& plan, const std::string& spec_path);

struct RunnerOptions {
  bool progress = false;                       ///< draw a progress bar on stderr
  const std::atomic<bool>* stop = nullptr;     ///< checked between groups: no new group starts once set
  /// Called (serially) for each group written, with its description; e.g. to report failures.
  std::function<void(const GroupRecord&, const std::string&)> on_group;
  Shard shard;                                 ///< only this shard's groups (default: all)
};

struct RunnerSummary {
  long long groups = 0, tasks = 0;                 ///< in the sweep (in the shard, for a shard)
  long long stored_before = 0;                     ///< of those, groups already in the store
  long long ran = 0, ran_tasks = 0, failed = 0;    ///< this session
  long long evaluations = 0;                       ///< this session
  double candidate_samples = 0;                    ///< this session
  double wall_time_s = 0;                          ///< this session
  bool interrupted = false;
  /// Under MPI (engine/distributed): messages rank 0 received and sent, their bytes, and the time rank 0 spent
  /// handling them (decoding, committing to the store): its serial cost per group, which bounds the ranks a
  /// sweep can use (docs/performance.md).
  long long messages = 0;
  double message_bytes = 0, coordinator_busy_s = 0;
  long long worker_threads = 0;  ///< threads of every worker rank together (their affinity masks decide them)
};

RunnerSummary run_sweep(const Plan& plan, Store& store, const RunnerOptions& options = {});

/// The serial end of a run, shared by run_sweep and the MPI coordinator (engine/distributed): writes each
/// finished group to the store in its own transaction, counts it into the summary, logs failures and draws
/// the progress bar. Construction works out what is left to run (schedule()) and the counts already stored.
class GroupWriter {
 public:
  GroupWriter(const Plan& plan, Store& store, const RunnerOptions& options);
  GroupWriter(const GroupWriter&) = delete;
  GroupWriter& operator=(const GroupWriter&) = delete;

  /// The groups to run, largest first.
  [[nodiscard]] const std::vector<long long>& todo() const { return todo_; }
  /// Writes one group (StoreError from the store propagates; nothing is counted then).
  void write(const GroupRecord& group);
  /// Clears the progress bar and returns the summary (wall time since construction; interrupted when the stop
  /// flag is set and groups of the run are missing from the store).
  RunnerSummary finish();

 private:
  const Plan& plan_;
  Store& store_;
  const RunnerOptions& options_;
  RunnerSummary summary_;
  std::vector<long long> todo_;
  std::optional<ProgressBar> bar_;
  std::chrono::steady_clock::time_point start_;
};

/// SIGINT and SIGTERM handling for `dampbench run`: the first signal sets the flag (no new group starts; groups
/// in flight finish and are stored), a second one ends the process at once (the store stays valid).
std::atomic<bool>& interrupt_flag();
void install_interrupt_handler();
void restore_interrupt_handler();

}  // namespace dampbench::sweep
