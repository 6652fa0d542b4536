#include "engine/cli/run_command.hpp"

#include <filesystem>
#include <iostream>
#include <optional>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/cli/sweep_outputs.hpp"
#include "engine/cli/output_manifest.hpp"
#include "engine/cli/system_benchmark.hpp"
#include "engine/common/error.hpp"
#include "engine/common/text_file.hpp"
#include "engine/distributed/mpi_runner.hpp"
#include "engine/record/record_options.hpp"
#include "engine/report/store_report.hpp"
#include "engine/sweep/runner.hpp"
#include "engine/sweep/schedule.hpp"
#include "engine/sweep/spec.hpp"
#include "engine/sweep/store.hpp"
#include "engine/sweep/tables.hpp"

namespace dampbench::cli {

namespace fs = std::filesystem;

void add_run_options(CLI::App* cmd, RunOptions& o) {
  cmd->add_option("preset", o.preset, "sweep file (presets: datasets/presets/*.toml)")->required();
  cmd->add_option("-o,--output", o.output_dir, "output folder (default results/<sweep name>)");
  cmd->add_option("--store", o.store, "SQLite store (default <output>/store.sqlite); an existing one is resumed");
  cmd->add_flag("--quiet", o.quiet, "no progress bar");
  cmd->add_flag("--fresh", o.fresh, "delete an existing store first instead of resuming it");
  cmd->add_flag("--no-report", o.no_report, "do not write <output>/report.html (dampbench report STORE writes it later)");
  cmd->add_option("--shard", o.shard,
                  "i/n: run only shard i of n (a fixed 1/n of the task groups, for job arrays) into its own store "
                  "(default <output>/shard-i-of-n.sqlite); `dampbench merge` joins the shards' stores");
}

sweep::Loader sweep_loader() {
  return [](const RecordOptions& o) { return load_record(o, true); };
}

namespace {

/// The groups left in the store run in this process (SIGINT/SIGTERM stop it between groups) or, under mpirun,
/// handed out to the other ranks.
sweep::RunnerSummary run_groups(std::optional<distributed::MpiJob>& job, const sweep::Plan& plan, sweep::Store& store,
                                const RunOptions& options, const sweep::Shard& shard) {
  sweep::RunnerOptions ro;
  ro.progress = !options.quiet;
  ro.shard = shard;
  // Ctrl-C reaches mpirun, which ends every rank; the store keeps every group committed so far.
  if (job && job->size() > 1) return distributed::coordinate(*job, plan, store, ro);
  ro.stop = &sweep::interrupt_flag();
  sweep::install_interrupt_handler();
  try {
    const sweep::RunnerSummary summary = sweep::run_sweep(plan, store, ro);
    sweep::restore_interrupt_handler();
    return summary;
  } catch (...) {
    sweep::restore_interrupt_handler();
    throw;
  }
}

/// Tables, summary and report into the output folder, and the files of a previous run it no longer writes removed.
void write_outputs(const sweep::Store& store, const sweep::StoreResults& results, const fs::path& out_dir,
                   const OutputInfo& info, bool no_report, std::string& report_note) {
  std::vector<std::string> written = write_sweep_outputs(results, out_dir, info, &std::cout);
  if (!no_report) {
    // The tables and the store are written: a report that cannot be drawn only warns.
    const std::string report_path = (out_dir / "report.html").string();
    try {
      write_text_file(report_path, report::store_report_html(store, sweep_loader()));
      report_note = ", report " + report_path;
      written.push_back("report.html");
    } catch (const std::exception& e) {
      std::cerr << fmt::format("warning: no HTML report: {}\n", e.what());
    }
  }
  std::vector<std::string> kept;
  const std::vector<std::string> stale = replace_output_manifest(out_dir, written, &kept);
  if (!stale.empty())
    std::cout << fmt::format("removed {} file(s) of the previous run into {} that this run does not write: {}\n",
                             stale.size(), out_dir.string(), fmt::join(stale, ", "));
  if (!kept.empty())
    std::cerr << fmt::format("warning: could not remove {} file(s) of the previous run into {}: {}\n", kept.size(),
                             out_dir.string(), fmt::join(kept, ", "));
}

/// The closing line: what ran, how fast, on how many ranks, and where the outputs are.
void print_run_summary(const sweep::Plan& plan, const sweep::StoreResults& results, const sweep::RunnerSummary& summary,
                       const std::optional<distributed::MpiJob>& job, const fs::path& out_dir,
                       const std::string& store_path, const std::string& report_note) {
  double stored_cs = 0, stored_wall = 0;
  for (const auto& g : results.groups) {
    stored_cs += g.candidate_samples;
    stored_wall += g.wall_time_s;
  }
  const std::string rate =
      summary.ran > 0 ? fmt::format("{:.3g} candidate-samples in {:.2f} s wall ({:.3g} candidate-samples/s)",
                                    summary.candidate_samples, summary.wall_time_s,
                                    summary.candidate_samples / summary.wall_time_s)
                      : fmt::format("nothing left to run, {:.2f} s wall (stored runs: {:.3g} candidate-samples/s)",
                                    summary.wall_time_s, stored_wall > 0 ? stored_cs / stored_wall : 0.0);
  const std::string ranks =
      job && job->size() > 1
          ? fmt::format(" on {} MPI ranks ({} worker threads; rank 0: {} messages, {:.3g} bytes, {:.3g} s handling "
                        "them, {:.3g} ms per group)",
                        job->size(), summary.worker_threads, summary.messages, summary.message_bytes, summary.coordinator_busy_s,
                        summary.ran > 0 ? 1e3 * summary.coordinator_busy_s / static_cast<double>(summary.ran) : 0.0)
          : "";
  std::cout << fmt::format("{}: {} task groups, {} tasks ({} run now, {} from the store, {} failed); {}{}; tables in {}, "
                           "store {}{}\n",
                           plan.spec().name, summary.groups, summary.tasks, summary.ran, summary.stored_before,
                           summary.failed, rate, ranks, out_dir.string(), store_path, report_note);
}

}  // namespace

int run_command(const RunOptions& options) {
  if (is_system_benchmark(options.preset))  // a [benchmark] preset: generate, fit, then test (system_benchmark.hpp)
    return run_system_benchmark(load_system_benchmark(options.preset), options.output_dir);
  // Under mpirun every rank builds the same plan; rank 0 owns the store and writes everything
  // (engine/distributed/mpi_runner.hpp), the other ranks only identify groups.
  std::optional<distributed::MpiJob> job;
  if (distributed::launched_by_mpi()) job.emplace();
  const bool rank0 = !job || job->rank() == 0;
  const sweep::Shard shard = options.shard.empty() ? sweep::Shard{} : sweep::parse_shard(options.shard);

  // The whole file, every dataset and every split are checked before anything runs.
  sweep::SweepSpec spec = sweep::load_sweep(options.preset);
  if (rank0)
    for (const auto& note : spec.notes) std::cerr << "note: " << note << "\n";
  const sweep::Plan plan(std::move(spec), sweep_loader());
  if (!rank0) {
    distributed::work(*job, plan);
    return 0;
  }
  for (const auto& part : plan.parts())
    for (const auto& d : part.datasets)
      if (!d.ok()) std::cerr << fmt::format("warning: dataset '{}' did not load: {}\n", d.signals.name, d.error);

  const fs::path out_dir = options.output_dir.empty() ? fs::path("results") / plan.spec().name : fs::path(options.output_dir);
  const std::string default_store =
      shard.whole() ? "store.sqlite" : fmt::format("shard-{}-of-{}.sqlite", shard.index + 1, shard.count);
  const std::string store_path = options.store.empty() ? (out_dir / default_store).string() : options.store;
  const sweep::StoreLock lock(store_path);  // before --fresh deletes anything: another run may be writing it
  if (options.fresh)
    for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(store_path + suffix);
  const std::string spec_path = fs::absolute(options.preset).lexically_normal().string();
  sweep::StoreHeader header = sweep::make_store_header(plan, spec_path);
  header.shard = shard.text();
  sweep::Store store = sweep::Store::create_or_resume(store_path, header);

  const sweep::RunnerSummary summary = run_groups(job, plan, store, options, shard);
  if (summary.interrupted) {
    std::cerr << fmt::format("{}: interrupted: {} of {} task groups are in {}; run the same command again to resume\n",
                             plan.spec().name, summary.stored_before + summary.ran, summary.groups, store_path);
    return kExitInterrupted;
  }
  if (!shard.whole()) {
    // One shard's tables would be partial: they come from the merged store.
    std::cout << fmt::format("{}: shard {}: {} of the sweep's {} task groups ({} run now, {} from the store, {} failed), "
                             "{:.2f} s wall, store {}; when every shard is done: dampbench merge OUT.sqlite "
                             "<the shards' stores>, then dampbench table OUT.sqlite --kind sweep\n",
                             plan.spec().name, shard.text(), summary.groups, plan.groups(), summary.ran,
                             summary.stored_before, summary.failed, summary.wall_time_s, store_path);
    return 0;
  }
  const sweep::StoreResults results(store, sweep_loader());
  std::string report_note;
  write_outputs(store, results, out_dir, {spec_path, store_path, summary}, options.no_report, report_note);
  print_run_summary(plan, results, summary, job, out_dir, store_path, report_note);
  return 0;
}

}  // namespace dampbench::cli
