// dampbench command line: models, simulate, fit, run, ... Every error, whatever raised it (CLI11, toml++,
// SQLite, the file system, dampbench), is printed as "dampbench: error: ..." on stderr and ends with the exit
// code of its class (engine/common/error.hpp ExitCode); nothing here crashes on user input.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <new>
#include <string>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <tbb/global_control.h>

#include "engine/cli/bench_command.hpp"
#include "engine/cli/compare_command.hpp"
#include "engine/cli/datasets_command.hpp"
#include "engine/cli/evaluate_command.hpp"
#include "engine/cli/fit_command.hpp"
#include "engine/cli/lssvm_command.hpp"
#include "engine/cli/merge_command.hpp"
#include "engine/cli/models_command.hpp"
#include "engine/cli/optimizers_command.hpp"
#include "engine/cli/report_command.hpp"
#include "engine/cli/run_command.hpp"
#include "engine/cli/sensitivity_command.hpp"
#include "engine/cli/export_command.hpp"
#include "engine/cli/inverse_command.hpp"
#include "engine/cli/simulate_command.hpp"
#include "engine/cli/structure_command.hpp"
#include "engine/cli/table_command.hpp"
#include "engine/cli/verify_command.hpp"
#include "engine/common/error.hpp"
#include "engine/distributed/mpi_runner.hpp"
#include "engine/kernels/isa.hpp"
#include "engine/model/metrics.hpp"

namespace {

using namespace dampbench::cli;

/// Keeps freed memory in the process for the next allocation. A fit allocates and frees vectors of a record's length
/// (10^4 to 10^5 samples: residuals, Jacobian columns, forces) many times per Levenberg–Marquardt iteration; under
/// glibc's defaults the larger ones are mapped and unmapped, or the heap's top trimmed, each time, and touching the
/// fresh pages again took 6 % of a Spencer law fit's CPU time (docs/performance.md, "Law-model fits over several
/// strokes"). Allocations do not change any result.
void keep_freed_memory() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);   // blocks under 32 MB (glibc's own ceiling for its dynamic threshold) from the heap
  mallopt(M_TRIM_THRESHOLD, 256 << 20);  // up to 256 MB of freed heap kept for reuse
#endif
}

/// A subcommand: its CLI11 node and what runs when the command line names it.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

/// Declares subcommand `name` of `parent`: `declare(app, options)` adds its options, `run(options)` runs it.
template <class Options, class Declare, class Run>
CLI::App* add_command(CLI::App* parent, std::vector<Command>& commands, const char* name, const char* description,
                      Declare declare, Run run) {
  auto options = std::make_shared<Options>();
  CLI::App* app = parent->add_subcommand(name, description);
  declare(app, *options);
  commands.push_back({app, [options, run] { return run(*options); }});
  return app;
}

/// Declares every subcommand on `app`, in the order --help lists them, with the options several of them share.
std::vector<Command> declare_commands(CLI::App& app, int& threads, std::string& isa) {
  std::vector<Command> commands;
  add_command<std::string>(&app, commands, "models", "list every model with parameter names, units and default bounds",
                           add_models_options, models_command);
  add_command<std::string>(&app, commands, "optimizers",
                           "list every optimizer's settings with their types, defaults, allowed values and meanings",
                           add_optimizers_options, optimizers_command);
  auto* simulate_cmd = add_command<SimulateOptions>(&app, commands, "simulate",
      "force of a model with given parameters under a displacement", add_simulate_options, simulate_command);
  add_command<StructureOptions>(&app, commands, "structure",
      "an identified damper in a building under an earthquake: peaks and their reductions, energies, time histories",
      add_structure_options, structure_command);
  add_command<InverseOptions>(&app, commands, "inverse",
      "the command (I, V, phi) that makes an identified damper give a desired force, or the on/off rule",
      add_inverse_options, inverse_command);
  add_command<ExportOptions>(&app, commands, "export",
      "an identified model as dependency-free C99 (dampbench_model.h/.c) for a controller or a real-time target",
      add_export_options, export_command);
  auto* fit_cmd = add_command<FitOptions>(&app, commands, "fit",
      "identify a model's parameters on a record with repeated optimizer runs", add_fit_options, fit_command);
  auto* run_cmd = add_command<RunOptions>(&app, commands, "run",
      "run a preset or sweep (datasets/presets/*.toml) and write its tables", add_run_options, run_command);
  add_command<MergeOptions>(&app, commands, "merge",
      "merge the stores of a sweep's shards (run --shard i/n) into one store", add_merge_options, merge_command);
  add_command<TableOptions>(&app, commands, "table", "print a table from a sweep's store", add_table_options,
                            table_command);
  add_command<ReportOptions>(&app, commands, "report",
      "an HTML report of a sweep's store: loops, convergence curves, run distributions, laws, tables",
      add_report_options, report_command);
  auto* verify_cmd = add_command<VerifyOptions>(&app, commands, "verify", "re-run stored tasks and compare bit for bit",
                                            add_verify_options, verify_command);
  auto* compare_cmd = add_command<CompareOptions>(&app, commands, "compare",
      "compare optimizers on the same model and data", add_compare_options, compare_command);
  auto* sensitivity_cmd = add_command<SensitivityOptions>(&app, commands, "sensitivity",
      "differential sensitivity of a model's parameters (crfd eqs. 4.1-4.3)", add_sensitivity_options,
      sensitivity_command);
  add_command<EvaluateOptions>(&app, commands, "evaluate", "metrics of given parameters on one or more records",
                               add_evaluate_options, evaluate_command);
  auto* datasets = app.add_subcommand("datasets", "synthetic grids of the papers that presets read as @generated/...");
  datasets->require_subcommand(1);
  add_command<DatasetsOptions>(datasets, commands, "generate",
      "write the grids ahead of first use (run does it when needed)", add_datasets_options, datasets_command);
  add_command<BoucWenDatasetsOptions>(datasets, commands, "bouc-wen-benchmark",
      "the hysteretic benchmark's training data for a seed, and a sine sweep check (t,y,u records)",
      add_bouc_wen_datasets_options, bouc_wen_datasets_command);
  auto* bench_cmd = add_command<BenchOptions>(&app, commands, "bench",
      "throughput of every model with 1 and 2 threads (docs/performance.md)", add_bench_options, bench_command);
  auto* lssvm_cmd = add_command<LssvmOptions>(&app, commands, "lssvm",
      "LS-SVM damper model (lssvm paper): GA-tuned, one-step and free-run test metrics", add_lssvm_options,
      lssvm_command);
  for (auto* cmd : {simulate_cmd, fit_cmd, run_cmd, sensitivity_cmd, verify_cmd, compare_cmd, lssvm_cmd})
    cmd->add_option("--threads", threads, "worker threads (default: all cores)")->check(CLI::Range(1, 4096));
  for (auto* cmd : {simulate_cmd, fit_cmd, run_cmd, sensitivity_cmd, verify_cmd, compare_cmd, lssvm_cmd, bench_cmd})
    cmd->add_option("--isa", isa, "vector instruction set of the kernels: sse2, avx2 or avx512 (default: the CPU's best)");
  return commands;
}

/// Prints the error the way every failure is printed and ends an MPI job's other ranks.
int fail(int code, const std::string& message) {
  std::fprintf(stderr, "dampbench: error: %s%s\n", dampbench::distributed::rank_prefix().c_str(), message.c_str());
  dampbench::distributed::abort_job_if_running(code);  // under mpirun: the other ranks must not wait for this one
  return code;
}

/// A command line CLI11 refused. It says "A subcommand is required" for a misspelt command too: this names the
/// word and lists the commands.
int usage_error(CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word.starts_with("-")) {
      if (word == "--threads" || word == "--isa") ++i;
      continue;
    }
    try {
      (void)app.get_subcommand(word);
    } catch (const CLI::OptionNotFound&) {
      std::string names;
      for (const CLI::App* sub : app.get_subcommands({})) names += (names.empty() ? "" : ", ") + sub->get_name();
      return fail(dampbench::kExitUsage, "unknown command '" + word + "' (commands: " + names + ")");
    }
    break;
  }
  return fail(dampbench::kExitUsage, std::string(e.what()) + " (run with --help for the options)");
}

/// Runs the parsed command under the thread limit and vector level asked for; every error becomes its exit code.
int run_parsed(const std::vector<Command>& commands, int threads, const std::string& isa, const char* isa_variable) {
  using namespace dampbench;
  try {
    std::optional<tbb::global_control> limit;
    if (threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    if (!isa.empty()) select_isa(isa, "--isa");
    else if (isa_variable && *isa_variable) select_isa(isa_variable, "DAMPBENCH_ISA");
    for (const Command& command : commands)
      if (command.app->parsed()) return command.run();
  } catch (const StoreError& e) {
    return fail(kExitStore, e.what());
  } catch (const DataError& e) {
    return fail(kExitData, e.what());
  } catch (const InputError& e) {
    return fail(kExitUsage, e.what());
  } catch (const std::filesystem::filesystem_error& e) {  // output folders and files
    return fail(kExitStore, e.what());
  } catch (const std::bad_alloc&) {
    return fail(kExitInternal, "out of memory");
  } catch (const std::exception& e) {
    return fail(kExitInternal, std::string("internal error (please report it): ") + e.what());
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  // DAMPBENCH_ISA first, so that --version shows the level it chose (a bad value is reported below).
  const char* isa_variable = std::getenv("DAMPBENCH_ISA");
  if (isa_variable && *isa_variable) try {
      dampbench::select_isa(isa_variable, "DAMPBENCH_ISA");
    } catch (const dampbench::InputError&) {
    }
  CLI::App app{"dampbench: identify damper models from test data and compare models and optimizers at scale"};
  app.set_version_flag("--version", std::string("dampbench ") + DAMPBENCH_VERSION + " (" + DAMPBENCH_BUILD_FLAGS + ")" +
                                        (dampbench::distributed::built_with_mpi() ? ", with MPI" : ", without MPI") +
                                        ", vector kernels " + dampbench::isa_summary());
  app.require_subcommand(1);
  int threads = 0;
  app.add_option("--threads", threads, "worker threads (default: all cores)")->check(CLI::Range(1, 4096));
  std::string isa;
  app.add_option("--isa", isa,
                 "vector instruction set of the kernels: sse2, avx2 or avx512 (default: the CPU's best, or the "
                 "DAMPBENCH_ISA variable); results are bit-identical within one level");
  const std::vector<Command> commands = declare_commands(app, threads, isa);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return usage_error(app, e, argc, argv);
  }
  return run_parsed(commands, threads, isa, isa_variable);
}
