#pragma once
// `mpirun -np K dampbench run SWEEP`: one sweep across the ranks of an MPI job (OpenMPI's C API; docs/design.md,
// "Results store and scale").
//
// Every rank reads the sweep file and its datasets (a cluster's shared file system) and builds the same plan.
// Rank 0 owns the store: it works out what is left (resume, shard), hands task groups to the workers on request,
// largest first (sweep/schedule.hpp), and commits each finished group in its own transaction (the same
// sweep::GroupWriter a single process uses), then writes the tables. Rank 0 does not identify groups itself: it
// waits for messages sleeping between polls (0.1 to 2 ms), so it takes little of its core. Each worker runs up to 2 × its
// threads groups at once with oneTBB, as `dampbench run` does in one process. A group's result depends only on
// its number and the plan, and travels as its exact bytes (group_codec.hpp), so the store is bit-identical to
// that of one process, for any rank and thread count.
//
// Faults: a rank that dies ends the job (mpirun's default; with srun, give --kill-on-bad-exit=1); rank 0 has
// committed every group it received, the store stays valid, and running the same command again resumes it (with
// or without mpirun). A store that cannot be written ends the job at once. Ranks whose executable, CPU features
// (glibc picks math code by them), sweep file or data differ from rank 0's are refused at their first message;
// a result that is not the group its rank was given is refused too. Waits sleep between tests instead of
// spinning (OpenMPI's blocking calls spin a core).
//
// Messages per group: one request (0 bytes), one assignment (8 bytes), one result (the record, a few kB; see
// docs/performance.md), plus one hello per worker.
#include <string>

#include "engine/sweep/plan.hpp"
#include "engine/sweep/runner.hpp"
#include "engine/sweep/store.hpp"

namespace dampbench::distributed {

/// True when this binary was built with MPI (CMake option DAMPBENCH_MPI).
bool built_with_mpi();

/// True when a launcher (mpirun, srun) started this process as a rank of a job of several ranks (OpenMPI's, PMI's
/// or PMIx's variables). MPI is never initialized otherwise, so the binary runs without mpirun, and a job of one
/// rank (mpirun -np 1, or srun of a job-array shard) is an ordinary process.
bool launched_by_mpi();

/// MPI_Init_thread … MPI_Finalize for one `dampbench run`. InputError when built without MPI.
class MpiJob {
 public:
  MpiJob();
  ~MpiJob();  ///< waits for every rank (sleeping, not spinning) and finalizes; skipped while an exception unwinds
  MpiJob(const MpiJob&) = delete;
  MpiJob& operator=(const MpiJob&) = delete;

  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int size() const { return size_; }

 private:
  int rank_ = 0, size_ = 1;
};

/// Ends every rank of the running MPI job with `exit_code` (MPI_Abort) after an error on this rank; returns
/// when no job is running. main() calls it after printing the error.
void abort_job_if_running(int exit_code);
/// "rank 2: " inside a job of several ranks, "" otherwise (prefix of error messages).
std::string rank_prefix();

/// Rank 0 of `job`: schedules `plan`'s groups left in `store` (options.shard) over the other ranks and writes
/// their results. Needs job.size() ≥ 2.
sweep::RunnerSummary coordinate(const MpiJob& job, const sweep::Plan& plan, sweep::Store& store,
                                const sweep::RunnerOptions& options);

/// Ranks > 0: runs the groups rank 0 hands out until it has none left.
void work(const MpiJob& job, const sweep::Plan& plan);

}  // namespace dampbench::distributed
