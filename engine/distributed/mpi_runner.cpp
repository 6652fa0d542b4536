#include "engine/distributed/mpi_runner.hpp"

#include <unistd.h>

#include <chrono>
#include <climits>
#include <cstdlib>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/distributed/group_codec.hpp"
#include "engine/sweep/fingerprint.hpp"

#ifdef DAMPBENCH_WITH_MPI
#include <mpi.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>
#endif

namespace dampbench::distributed {

bool launched_by_mpi() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(var)) return true;
  return false;
}

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
constexpr auto kPollInterval = std::chrono::microseconds(200);

/// What must be equal on every rank for their results to be the same bits: binary, sweep spec, datasets.
std::string plan_fingerprint(const sweep::Plan& plan) {
  std::string f = fmt::format("dampbench {} ({}), spec {}, {} groups, datasets", sweep::dampbench_version(),
                              sweep::build_flags(), plan.spec().hash, plan.groups());
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

/// Waits until every rank calls it, sleeping between tests (a blocking barrier would spin a core each).
void sleeping_barrier() {
  MPI_Request request;
  check(MPI_Ibarrier(MPI_COMM_WORLD, &request), "MPI_Ibarrier");
  for (int done = 0;;) {
    check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), "MPI_Test");
    if (done) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

}  // namespace

MpiJob::MpiJob() {
  int provided = 0;
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided), "MPI_Init_thread");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  g_job = {true, rank_, size_};
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
  std::vector<int> in_flight(static_cast<std::size_t>(job.size()), 0);
  long long in_flight_total = 0;
  std::exception_ptr write_error;
  long long messages = 0;
  double message_bytes = 0, busy_s = 0;
  while (finished_workers < job.size() - 1 || in_flight_total > 0) {
    int arrived = 0;
    MPI_Status status;
    check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status), "MPI_Iprobe");
    if (!arrived) {
      std::this_thread::sleep_for(kPollInterval);
      continue;
    }
    const auto busy_from = std::chrono::steady_clock::now();
    const int from = status.MPI_SOURCE;
    const std::string bytes = receive_bytes(status);
    ++messages;
    message_bytes += static_cast<double>(bytes.size());
    switch (status.MPI_TAG) {
      case kHello: {
        const auto newline = bytes.rfind('\n');
        const std::string theirs = bytes.substr(0, newline), host = bytes.substr(newline + 1);
        if (theirs != fingerprint)
          throw InputError(fmt::format(
              "rank {} (host {}) is not running the same computation as rank 0 (host {}): it has\n  {}\nrank 0 has\n"
              "  {}\n(identical results need the same binary, sweep file and data on every node)",
              from, host, host_name(), theirs, fingerprint));
        break;
      }
      case kRequest: {
        const bool stop = write_error || (options.stop && options.stop->load());
        long long group = kNoMoreGroups;
        if (!stop && next < todo.size()) {
          group = todo[next++];
          ++in_flight[static_cast<std::size_t>(from)];
          ++in_flight_total;
        } else {
          ++finished_workers;
        }
        check(MPI_Send(&group, 1, MPI_LONG_LONG, from, kAssign, MPI_COMM_WORLD), "MPI_Send");
        ++messages;
        message_bytes += sizeof group;
        break;
      }
      case kResult: {
        sweep::GroupRecord record = decode_group(bytes);
        --in_flight[static_cast<std::size_t>(from)];
        --in_flight_total;
        if (write_error) break;
        try {
          writer.write(record);
        } catch (...) {
          write_error = std::current_exception();  // no new group is handed out; those in flight are drained
        }
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
  if (write_error) std::rethrow_exception(write_error);
  return summary;
}

void work(const MpiJob&, const sweep::Plan& plan) {
  send_bytes(plan_fingerprint(plan) + "\n" + host_name(), 0, kHello);
  std::mutex mpi;  // MPI_THREAD_SERIALIZED: one MPI call at a time from this rank's threads
  const auto tokens = static_cast<std::size_t>(2 * std::max(1, tbb::this_task_arena::max_concurrency()));
  using Bytes = std::shared_ptr<std::string>;
  tbb::parallel_pipeline(
      tokens,
      tbb::make_filter<void, long long>(tbb::filter_mode::serial_in_order,
                                        [&](tbb::flow_control& fc) -> long long {
                                          long long group = kNoMoreGroups;
                                          {
                                            const std::lock_guard lock(mpi);
                                            check(MPI_Send(nullptr, 0, MPI_BYTE, 0, kRequest, MPI_COMM_WORLD), "MPI_Send");
                                            check(MPI_Recv(&group, 1, MPI_LONG_LONG, 0, kAssign, MPI_COMM_WORLD,
                                                           MPI_STATUS_IGNORE),
                                                  "MPI_Recv");
                                          }
                                          if (group == kNoMoreGroups) fc.stop();
                                          return group;
                                        }) &
          tbb::make_filter<long long, Bytes>(
              tbb::filter_mode::parallel,
              [&](long long i) { return std::make_shared<std::string>(encode_group(sweep::run_group(plan, i))); }) &
          tbb::make_filter<Bytes, void>(tbb::filter_mode::serial_out_of_order, [&](const Bytes& bytes) {
            const std::lock_guard lock(mpi);
            send_bytes(*bytes, 0, kResult);
          }));
}

#endif

}  // namespace dampbench::distributed
