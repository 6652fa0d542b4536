// dampbench command line: models, simulate, fit, run, ... Every error, whatever raised it (CLI11, toml++,
// SQLite, the file system, dampbench), is printed as "dampbench: error: ..." on stderr and ends with the exit
// code of its class (engine/common/error.hpp ExitCode; README "Exit codes"); nothing here crashes on user input.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <string>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <tbb/global_control.h>

#include "engine/cli/commands.hpp"
#include "engine/cli/bench_command.hpp"
#include "engine/cli/compare_command.hpp"
#include "engine/cli/lssvm_command.hpp"
#include "engine/cli/report_command.hpp"
#include "engine/cli/sweep_commands.hpp"
#include "engine/common/error.hpp"
#include "engine/distributed/mpi_runner.hpp"
#include "engine/kernels/isa.hpp"
#include "engine/model/metrics.hpp"

namespace {

using namespace dampbench::cli;

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

}  // namespace

int main(int argc, char** argv) {
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
  std::vector<Command> commands;

  add_command<std::string>(&app, commands, "models", "list every model with parameter names, units and default bounds",
      [](CLI::App* c, std::string& format) {
        format = "md";
        c->add_option("--format", format, "md or json");
      },
      models_command);
  auto* simulate_cmd = add_command<SimulateOptions>(&app, commands, "simulate",
      "force of a model with given parameters under a displacement",
      [](CLI::App* c, SimulateOptions& sim) {
        c->add_option("--model", sim.model, "model id (see `dampbench models`)");
        c->add_option("--fixture", sim.fixture, "published law fixture instead of --model, e.g. mfm.table3");
        c->add_option("--laws", sim.laws, "parameter laws, e.g. 'c0=poly(I,1);alpha=poly(I,1)'");
        c->add_option("--params", sim.params, "parameter (or law coefficient) values in SI, name=value,...");
        c->add_option("--input", sim.input.path, "displacement record (CSV); t and x are used");
        add_data_options(c, sim.input);
        c->add_option("--sine", sim.sine, "sinusoid: amp=m,freq=Hz (or vpeak=m/s),cycles=N,fs=Hz");
        c->add_option("--noise-rel", sim.noise_rel, "Gaussian noise, std = R x RMS(force)");
        c->add_option("--seed", sim.seed, "noise seed");
        c->add_option("-o,--output", sim.output, "output CSV (t,x,v,a,F in SI); default stdout");
      },
      simulate_command);
  auto* fit_cmd = add_command<FitOptions>(&app, commands, "fit",
      "identify a model's parameters on a record with repeated optimizer runs",
      [](CLI::App* c, FitOptions& fit) {
        c->add_option("--model", fit.model, "model id")->required();
        c->add_option("--data", fit.paths, "test record (CSV); repeat for several conditions fitted at once")->required();
        c->add_option("--laws", fit.laws, "parameter laws in operating variables, e.g. 'c0=poly(I,1);alpha=poly(I,1)'");
        add_data_options(c, fit.data);
        c->add_option("--metric", fit.metric, dampbench::metric_names() + " (default of_abs)");
        c->add_option("--optimizer", fit.optimizer,
                      "pso, ga, aga, de, ga-lm, ... (default: ga-lm for models with internal states, else pso)");
        c->add_option("--optimizer-settings", fit.optimizer_settings, "algorithm settings, e.g. pc=0.6,pm=0.03 or variant=constriction");
        c->add_option("--pop", fit.population, "population size (default 24 for ga-lm on internal states, else 50)");
        c->add_option("--iters", fit.iterations, "iterations (default 30 for ga-lm on internal states, else 100)");
        c->add_option("--runs", fit.runs, "independent runs (default 4 for internal states, else 50)");
        c->add_option("--seed", fit.seed, "seed (default 1)");
        c->add_option("--bounds", fit.bounds, "bounds in SI, name=lo:hi,...");
        c->add_option("--format", fit.format, "md (default) or json");
        c->add_option("--report", fit.report, "also write an HTML report (loops, convergence, runs) to this file");
      },
      fit_command);
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
      "differential sensitivity of a model's parameters (crfd eqs. 4.1-4.3)",
      [](CLI::App* c, SensitivityOptions& sens) {
        c->add_option("--model", sens.model, "model id")->required();
        c->add_option("--params", sens.params, "parameter values in SI (repeat for several cases)")->required();
        c->add_option("--sine", sens.sines, "sinusoid input (once, or once per --params)");
        c->add_option("--data", sens.paths, "record input instead of --sine (once, or once per --params)");
        add_data_options(c, sens.data);
        c->add_option("--points", sens.points, "grid points per parameter (default 21)");
        c->add_option("--range", sens.range, "relative half-range (default 0.5 = ±50 %)");
        c->add_option("--objective", sens.objective, "rms (of the model force, default) or a metric name");
        c->add_flag("--normalized", sens.normalized, "report S_z·|z| (elasticity) instead of S_z as printed");
        c->add_option("--format", sens.format, "md (default) or json");
      },
      sensitivity_command);
  add_command<EvaluateOptions>(&app, commands, "evaluate", "metrics of given parameters on one or more records",
      [](CLI::App* c, EvaluateOptions& eval) {
        c->add_option("--model", eval.model, "model id")->required();
        c->add_option("--laws", eval.laws, "parameter laws (then --params gives their coefficients)");
        c->add_option("--params", eval.params, "parameter values in SI, name=value,...")->required();
        c->add_option("--data", eval.paths, "record(s)")->required();
        add_data_options(c, eval.data);
        c->add_option("--format", eval.format, "md (default) or json");
      },
      evaluate_command);
  auto* datasets = app.add_subcommand("datasets", "synthetic grids of the papers that presets read as @generated/...");
  datasets->require_subcommand(1);
  add_command<DatasetsOptions>(datasets, commands, "generate",
      "write the grids ahead of first use (run does it when needed)", add_datasets_options, datasets_command);
  auto* bench_cmd = add_command<BenchOptions>(&app, commands, "bench",
      "throughput of every model with 1 and 2 threads (docs/performance.md)", add_bench_options, bench_command);
  auto* lssvm_cmd = add_command<LssvmOptions>(&app, commands, "lssvm",
      "LS-SVM damper model (lssvm paper): GA-tuned, one-step and free-run test metrics", add_lssvm_options,
      lssvm_command);
  for (auto* cmd : {simulate_cmd, fit_cmd, run_cmd, sensitivity_cmd, verify_cmd, compare_cmd, lssvm_cmd})
    cmd->add_option("--threads", threads, "worker threads (default: all cores)")->check(CLI::Range(1, 4096));
  for (auto* cmd : {simulate_cmd, fit_cmd, run_cmd, sensitivity_cmd, verify_cmd, compare_cmd, lssvm_cmd, bench_cmd})
    cmd->add_option("--isa", isa, "vector instruction set of the kernels: sse2, avx2 or avx512 (default: the CPU's best)");

  using namespace dampbench;
  auto fail = [](int code, const std::string& message) {
    std::fprintf(stderr, "dampbench: error: %s%s\n", distributed::rank_prefix().c_str(), message.c_str());
    distributed::abort_job_if_running(code);  // under mpirun: the other ranks must not wait for this one
    return code;
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // CLI11 says "A subcommand is required" for a misspelt command too: name it and list the commands.
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
        return fail(kExitUsage, "unknown command '" + word + "' (commands: " + names + ")");
      }
      break;
    }
    return fail(kExitUsage, std::string(e.what()) + " (run with --help for the options)");
  }

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
