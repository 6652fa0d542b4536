#include "engine/distributed/mpi_runner.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <iostream>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <memory>
#include <mutex>
#include <set>
#include <thread>
#include <tuple>
#include <vector>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/random.hpp"
#include "engine/distributed/group_codec.hpp"
#include "engine/sweep/fingerprint.hpp"

#ifdef DAMPBENCH_WITH_MPI
#include <mpi.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>
#endif

namespace dampbench::distributed {

int launcher_job_size() {
  // OpenMPI's mpirun, MPICH/PMI (also srun --mpi=pmi2), Slurm's srun with PMIx (whose own variables hold no size).
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* v = std::getenv(var)) return std::max(1, std::atoi(v));
  if (!std::getenv("PMIX_RANK")) return 1;
  const char* tasks = std::getenv("SLURM_STEP_NUM_TASKS");
  return tasks ? std::max(1, std::atoi(tasks)) : 2;
}

bool launched_by_mpi() { return launcher_job_size() > 1; }

namespace {
/// This process's job once MPI is initialized, until it is finalized (for abort_job_if_running and rank_prefix,
/// which main() calls after the MpiJob has gone out of scope with the exception).
struct RunningJob {
  bool running = false;
  int rank = 0, size = 1;
} g_job;
}  // namespace

std::string rank_prefix() { return g_job.running && g_job.size > 1 ? fmt::format("rank {}: ", g_job.rank) : ""; }

#ifndef DAMPBENCH_WITH_MPI

bool built_with_mpi() { return false; }

MpiJob::MpiJob() {
  throw InputError(
      "this dampbench was built without MPI (cmake -DDAMPBENCH_MPI=ON, with Debian's libopenmpi-dev) but is "
      "started by mpirun: every rank would run the whole sweep; use --shard i/n for job arrays instead");
}
MpiJob::~MpiJob() = default;
void abort_job_if_running(int) {}
sweep::RunnerSummary coordinate(const MpiJob&, const sweep::Plan&, sweep::Store&, const sweep::RunnerOptions&) {
  throw InputError("built without MPI");
}
void work(const MpiJob&, const sweep::Plan&) { throw InputError("built without MPI"); }

#else

bool built_with_mpi() { return true; }

namespace {

enum Tag : int { kHello = 1, kRequest = 2, kAssign = 3, kResult = 4 };
constexpr long long kNoMoreGroups = -1;
// Polling between messages: rank 0 sleeps from kPollInterval up to kMaxPollInterval, doubling while nothing
// arrives, so that an idle rank 0 wakes at most ~500 times a second on a core a worker uses, and a burst of
// results is still taken at once. A worker waiting for its assignment polls every kPollInterval.
constexpr auto kPollInterval = std::chrono::microseconds(100);
constexpr auto kMaxPollInterval = std::chrono::microseconds(2000);

/// Hash of this process's executable: two builds of one version differ here.
std::string executable_hash() {
  std::ifstream in("/proc/self/exe", std::ios::binary);
  std::uint64_t h = hash_name("executable");
  std::vector<char> chunk(1 << 16);
  while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0) {
    h = hash_key({h, hash_name(std::string_view(chunk.data(), static_cast<std::size_t>(in.gcount())))});
    if (!in) break;
  }
  return fmt::format("{:016x}", h);
}

/// The vector ISA levels glibc's math functions choose between at run time (their results may differ).
/// The CPU features glibc's scalar libm picks its code by (FMA, AVX2). The vector level of the kernels is in
/// build_flags(), so AVX-512 and AVX2 nodes pinned to one level (DAMPBENCH_ISA) can work together; a native
/// build compiles everything for its CPU and also compares AVX-512.
std::string cpu_features() {
  std::string f;
  __builtin_cpu_init();
#ifdef DAMPBENCH_NATIVE_BUILD
  if (__builtin_cpu_supports("avx512f")) f += "avx512f ";
#endif
  if (__builtin_cpu_supports("avx2")) f += "avx2 ";
  if (__builtin_cpu_supports("fma")) f += "fma ";
  return f.empty() ? "sse2" : f.substr(0, f.size() - 1);
}

/// What must be equal on every rank for their results to be the same bits: binary, the CPU's math paths, sweep
/// spec, datasets.
std::string plan_fingerprint(const sweep::Plan& plan) {
  std::string f = fmt::format("dampbench {} ({}), executable {}, cpu {}, spec {}, {} groups, datasets",
                              sweep::dampbench_version(), sweep::build_flags(), executable_hash(), cpu_features(),
                              plan.spec().hash, plan.groups());
  for (const auto& part : plan.parts())
    for (const auto& d : part.datasets) f += " " + d.hash;
  return f;
}

std::string host_name() {
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  return name;
}

void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) {
    char text[MPI_MAX_ERROR_STRING];
    int len = 0;
    MPI_Error_string(rc, text, &len);
    throw StoreError(fmt::format("MPI: {} failed: {}", what, std::string(text, static_cast<std::size_t>(len))));
  }
}

void send_bytes(const std::string& bytes, int to, int tag) {
  if (bytes.size() > static_cast<std::size_t>(INT_MAX))
    throw StoreError(fmt::format("MPI: a message of {} bytes is too large", bytes.size()));
  check(MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD), "MPI_Send");
}

std::string receive_bytes(const MPI_Status& probed) {
  int count = 0;
  check(MPI_Get_count(&probed, MPI_BYTE, &count), "MPI_Get_count");
  std::string bytes(static_cast<std::size_t>(count), '\0');
  check(MPI_Recv(bytes.data(), count, MPI_BYTE, probed.MPI_SOURCE, probed.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
        "MPI_Recv");
  return bytes;
}

/// Waits for a non-blocking operation, sleeping between tests: OpenMPI's blocking calls spin a core, which on
/// a shared or oversubscribed node takes it from the ranks that compute.
void wait_sleeping(MPI_Request& request, std::chrono::microseconds interval) {
  for (int done = 0;;) {
    check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), "MPI_Test");
    if (done) return;
    std::this_thread::sleep_for(interval);
  }
}

/// Waits until every rank calls it, sleeping.
void sleeping_barrier() {
  MPI_Request request;
  check(MPI_Ibarrier(MPI_COMM_WORLD, &request), "MPI_Ibarrier");
  wait_sleeping(request, std::chrono::milliseconds(1));
}

/// Refuses a result that is not the group `from` was given, or whose identity differs from the plan's.
void check_result(const sweep::Plan& plan, const sweep::GroupRecord& r, int from, std::set<long long>& assigned) {
  if (assigned.erase(r.index) == 0)
    throw StoreError(fmt::format("MPI: rank {} sent a result for task group {}, which it was not given", from, r.index));
  const sweep::GroupRef g = plan.group(r.index);
  if (std::tie(g.part, g.split, g.fitset, g.model, g.optimizer, g.metric, g.runs, g.task_key) !=
      std::tie(r.part, r.split, r.fitset, r.model, r.optimizer, r.metric, r.runs, r.task_key))
    throw StoreError(fmt::format("MPI: rank {} sent task group {} with another identity than this plan's", from, r.index));
}

/// A worker's hello, "host\nthreads cores\nfingerprint" (work()): counts its threads, notes once that a launcher
/// confines workers to fewer threads than their node has cores, and refuses a worker that computes differently.
void check_hello(const std::string& bytes, int from, const std::string& fingerprint, long long& worker_threads,
                 int& confined) {
  const auto first = bytes.find('\n'), second = bytes.find('\n', first + 1);
  const std::string host = bytes.substr(0, first), theirs = bytes.substr(second == std::string::npos ? 0 : second + 1);
  int threads = 0, cores = 0;
  std::sscanf(bytes.substr(first + 1, second - first - 1).c_str(), "%d %d", &threads, &cores);
  worker_threads += threads;
  if (threads < cores && ++confined == 1)
    std::cerr << fmt::format("note: rank {} runs {} thread(s) on host {}, which has {} cores: the launcher confines "
                             "it (mpirun binds ranks to cores by default); with one rank per node, give mpirun "
                             "--bind-to none\n",
                             from, threads, host, cores);
  if (theirs != fingerprint)
    throw InputError(fmt::format(
        "rank {} (host {}) is not running the same computation as rank 0 (host {}): it has\n  {}\nrank 0 has\n"
        "  {}\n(identical results need the same binary, CPU type, sweep file and data on every node)",
        from, host, host_name(), theirs, fingerprint));
}

}  // namespace

MpiJob::MpiJob() {
  int provided = 0;
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided), "MPI_Init_thread");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  g_job = {true, rank_, size_};
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);  // failures become messages (check), then MPI_Abort
  if (provided < MPI_THREAD_SERIALIZED)
    throw StoreError("MPI: this MPI library does not allow calls from several threads (MPI_THREAD_SERIALIZED)");
}

MpiJob::~MpiJob() {
  if (std::uncaught_exceptions() > 0) return;  // the error is printed, then abort_job_if_running ends the job
  try {
    sleeping_barrier();
  } catch (...) {
  }
  MPI_Finalize();
  g_job.running = false;
}

void abort_job_if_running(int exit_code) {
  if (g_job.running) MPI_Abort(MPI_COMM_WORLD, exit_code);
}

sweep::RunnerSummary coordinate(const MpiJob& job, const sweep::Plan& plan, sweep::Store& store,
                                const sweep::RunnerOptions& options) {
  sweep::GroupWriter writer(plan, store, options);
  const std::vector<long long>& todo = writer.todo();
  const std::string fingerprint = plan_fingerprint(plan);
  std::size_t next = 0;
  int finished_workers = 0;          // workers told there is nothing more
  std::vector<std::set<long long>> assigned(static_cast<std::size_t>(job.size()));
  long long in_flight = 0;
  long long messages = 0, worker_threads = 0;
  int confined = 0;  // workers with fewer threads than their node has cores
  auto poll = kPollInterval;
  double message_bytes = 0, busy_s = 0;
  while (finished_workers < job.size() - 1 || in_flight > 0) {
    int arrived = 0;
    MPI_Status status;
    check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status), "MPI_Iprobe");
    if (!arrived) {
      std::this_thread::sleep_for(poll);
      poll = std::min(2 * poll, kMaxPollInterval);
      continue;
    }
    poll = kPollInterval;
    const auto busy_from = std::chrono::steady_clock::now();
    const int from = status.MPI_SOURCE;
    const std::string bytes = receive_bytes(status);
    ++messages;
    message_bytes += static_cast<double>(bytes.size());
    switch (status.MPI_TAG) {
      case kHello:
        check_hello(bytes, from, fingerprint, worker_threads, confined);
        break;
      case kRequest: {
        long long group = kNoMoreGroups;
        if (next < todo.size() && !(options.stop && options.stop->load())) {
          group = todo[next++];
          assigned[static_cast<std::size_t>(from)].insert(group);
          ++in_flight;
        } else {
          ++finished_workers;
        }
        check(MPI_Send(&group, 1, MPI_LONG_LONG, from, kAssign, MPI_COMM_WORLD), "MPI_Send");
        ++messages;
        message_bytes += sizeof group;
        break;
      }
      case kResult: {
        const sweep::GroupRecord record = decode_group(bytes);
        check_result(plan, record, from, assigned[static_cast<std::size_t>(from)]);
        --in_flight;
        // A store that cannot be written ends the job at once (main prints the error, then MPI_Abort): every
        // group committed so far stays in the store; the groups in flight run again on resume.
        writer.write(record);
        break;
      }
      default:
        throw StoreError(fmt::format("MPI: unexpected message (tag {}) from rank {}", status.MPI_TAG, from));
    }
    busy_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - busy_from).count();
  }
  sweep::RunnerSummary summary = writer.finish();
  summary.messages = messages;
  summary.message_bytes = message_bytes;
  summary.coordinator_busy_s = busy_s;
  summary.worker_threads = worker_threads;
  return summary;
}

void work(const MpiJob&, const sweep::Plan& plan) {
  send_bytes(fmt::format("{}\n{} {}\n{}", host_name(), tbb::this_task_arena::max_concurrency(),
                         std::thread::hardware_concurrency(), plan_fingerprint(plan)),
             0, kHello);
  std::mutex mpi;  // MPI_THREAD_SERIALIZED: one MPI call at a time from this rank's threads
  const auto tokens = static_cast<std::size_t>(2 * std::max(1, tbb::this_task_arena::max_concurrency()));
  using Bytes = std::shared_ptr<std::string>;
  RecordFitCache record_fits;  // this rank's groups that fit the same records alone share those fits
  sweep::GroupFitCache group_fits;  // and the fits of groups that others hold to
  tbb::parallel_pipeline(
      tokens,
      tbb::make_filter<void, long long>(tbb::filter_mode::serial_in_order,
                                        [&](tbb::flow_control& fc) -> long long {
                                          long long group = kNoMoreGroups;
                                          {
                                            const std::lock_guard lock(mpi);
                                            check(MPI_Send(nullptr, 0, MPI_BYTE, 0, kRequest, MPI_COMM_WORLD), "MPI_Send");
                                            MPI_Request reply;
                                            check(MPI_Irecv(&group, 1, MPI_LONG_LONG, 0, kAssign, MPI_COMM_WORLD, &reply),
                                                  "MPI_Irecv");
                                            wait_sleeping(reply, kPollInterval);
                                          }
                                          if (group == kNoMoreGroups) fc.stop();
                                          return group;
                                        }) &
          tbb::make_filter<long long, Bytes>(
              tbb::filter_mode::parallel,
              [&](long long i) {
                return std::make_shared<std::string>(encode_group(sweep::run_group(plan, i, &record_fits, &group_fits)));
              }) &
          tbb::make_filter<Bytes, void>(tbb::filter_mode::serial_out_of_order, [&](const Bytes& bytes) {
            const std::lock_guard lock(mpi);
            send_bytes(*bytes, 0, kResult);
          }));
}

#endif

}  // namespace dampbench::distributed
