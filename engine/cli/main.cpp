// dampbench command line: models, simulate, fit, run. Bad input ends with "dampbench: error: ..." and
// exit code 2; nothing here crashes on user input.
#include <cstdio>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <tbb/global_control.h>

#include "engine/cli/commands.hpp"
#include "engine/cli/bench_command.hpp"
#include "engine/cli/compare_command.hpp"
#include "engine/cli/lssvm_command.hpp"
#include "engine/cli/sweep_commands.hpp"
#include "engine/common/error.hpp"

namespace {


}  // namespace

int main(int argc, char** argv) {
  using namespace dampbench::cli;
  CLI::App app{"dampbench: identify damper models from test data and compare models and optimizers at scale"};
  app.set_version_flag("--version", std::string("dampbench ") + DAMPBENCH_VERSION + " (" + DAMPBENCH_BUILD_FLAGS + ")");
  app.require_subcommand(1);
  int threads = 0;
  app.add_option("--threads", threads, "worker threads (default: all cores)")->check(CLI::Range(1, 4096));

  std::string models_format = "md";
  auto* models = app.add_subcommand("models", "list every model with parameter names, units and default bounds");
  models->add_option("--format", models_format, "md or json");

  SimulateOptions sim;
  auto* simulate = app.add_subcommand("simulate", "force of a model with given parameters under a displacement");
  simulate->add_option("--model", sim.model, "model id (see `dampbench models`)");
  simulate->add_option("--fixture", sim.fixture, "published law fixture instead of --model, e.g. mfm.table3");
  simulate->add_option("--laws", sim.laws, "parameter laws, e.g. 'c0=poly(I,1);alpha=poly(I,1)'");
  simulate->add_option("--params", sim.params, "parameter (or law coefficient) values in SI, name=value,...");
  simulate->add_option("--input", sim.input.path, "displacement record (CSV); t and x are used");
  add_data_options(simulate, sim.input);
  simulate->add_option("--sine", sim.sine, "sinusoid: amp=m,freq=Hz (or vpeak=m/s),cycles=N,fs=Hz");
  simulate->add_option("--noise-rel", sim.noise_rel, "Gaussian noise, std = R x RMS(force)");
  simulate->add_option("--seed", sim.seed, "noise seed");
  simulate->add_option("-o,--output", sim.output, "output CSV (t,x,v,a,F in SI); default stdout");

  FitOptions fit;
  auto* fitc = app.add_subcommand("fit", "identify a model's parameters on a record with repeated optimizer runs");
  fitc->add_option("--model", fit.model, "model id")->required();
  fitc->add_option("--data", fit.paths, "test record (CSV); repeat for several conditions fitted at once")->required();
  fitc->add_option("--laws", fit.laws, "parameter laws in operating variables, e.g. 'c0=poly(I,1);alpha=poly(I,1)'");
  add_data_options(fitc, fit.data);
  fitc->add_option("--metric", fit.metric, "of_abs (default), of_sq, rmse, nrmse, mae");
  fitc->add_option("--optimizer", fit.optimizer, "pso (default), ga, aga, de, ...");
  fitc->add_option("--optimizer-settings", fit.optimizer_settings, "algorithm settings, e.g. pc=0.6,pm=0.03 or variant=constriction");
  fitc->add_option("--pop", fit.population, "population size (default 50)");
  fitc->add_option("--iters", fit.iterations, "iterations (default 100)");
  fitc->add_option("--runs", fit.runs, "independent runs (default 50)");
  fitc->add_option("--seed", fit.seed, "seed (default 1)");
  fitc->add_option("--bounds", fit.bounds, "bounds in SI, name=lo:hi,...");
  fitc->add_option("--format", fit.format, "md (default) or json");

  RunOptions run;
  auto* runc = app.add_subcommand("run", "run a preset or sweep (datasets/presets/*.toml) and write its tables");
  add_run_options(runc, run);
  TableOptions tab;
  auto* tablec = app.add_subcommand("table", "print a table from a sweep's store");
  add_table_options(tablec, tab);
  VerifyOptions ver;
  auto* verifyc = app.add_subcommand("verify", "re-run stored tasks and compare bit for bit");
  add_verify_options(verifyc, ver);
  CompareOptions cmp;
  auto* comparec = app.add_subcommand("compare", "compare optimizers on the same model and data");
  add_compare_options(comparec, cmp);
  SensitivityOptions sens;
  auto* sensc = app.add_subcommand("sensitivity", "differential sensitivity of a model's parameters (crfd eqs. 4.1-4.3)");
  sensc->add_option("--model", sens.model, "model id")->required();
  sensc->add_option("--params", sens.params, "parameter values in SI (repeat for several cases)")->required();
  sensc->add_option("--sine", sens.sines, "sinusoid input (once, or once per --params)");
  sensc->add_option("--data", sens.paths, "record input instead of --sine (once, or once per --params)");
  add_data_options(sensc, sens.data);
  sensc->add_option("--points", sens.points, "grid points per parameter (default 21)");
  sensc->add_option("--range", sens.range, "relative half-range (default 0.5 = ±50 %)");
  sensc->add_option("--objective", sens.objective, "rms (of the model force, default) or a metric name");
  sensc->add_flag("--normalized", sens.normalized, "report S_z·|z| (elasticity) instead of S_z as printed");
  sensc->add_option("--format", sens.format, "md (default) or json");
  EvaluateOptions eval;
  auto* evalc = app.add_subcommand("evaluate", "metrics of given parameters on one or more records");
  evalc->add_option("--model", eval.model, "model id")->required();
  evalc->add_option("--laws", eval.laws, "parameter laws (then --params gives their coefficients)");
  evalc->add_option("--params", eval.params, "parameter values in SI, name=value,...")->required();
  evalc->add_option("--data", eval.paths, "record(s)")->required();
  add_data_options(evalc, eval.data);
  evalc->add_option("--format", eval.format, "md (default) or json");
  DatasetsOptions datasets;
  auto* datasetsc = app.add_subcommand("datasets", "synthetic grids of the papers that presets read as @generated/...");
  datasetsc->require_subcommand(1);
  auto* generatec = datasetsc->add_subcommand("generate", "write the grids ahead of first use (run does it when needed)");
  add_datasets_options(generatec, datasets);
  BenchOptions bench;
  auto* benchc = app.add_subcommand("bench", "throughput of every model with 1 and 2 threads (docs/performance.md)");
  add_bench_options(benchc, bench);
  for (auto* cmd : {simulate, fitc, runc, sensc, verifyc, comparec})
    cmd->add_option("--threads", threads, "worker threads (default: all cores)")->check(CLI::Range(1, 4096));

  LssvmOptions lss;
  auto* lssvmc = app.add_subcommand("lssvm", "LS-SVM damper model (lssvm paper): GA-tuned, one-step and free-run test metrics");
  add_lssvm_options(lssvmc, lss);
  lssvmc->add_option("--threads", threads, "worker threads (default: all cores)")->check(CLI::Range(1, 4096));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  try {
    std::optional<tbb::global_control> limit;
    if (threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    if (models->parsed()) return models_command(models_format);
    if (simulate->parsed()) return simulate_command(sim);
    if (fitc->parsed()) return fit_command(fit);
    if (runc->parsed()) return run_command(run);
    if (sensc->parsed()) return sensitivity_command(sens);
    if (lssvmc->parsed()) return lssvm_command(lss);
    if (tablec->parsed()) return table_command(tab);
    if (verifyc->parsed()) return verify_command(ver);
    if (comparec->parsed()) return compare_command(cmp);
    if (benchc->parsed()) return bench_command(bench);
    if (evalc->parsed()) return evaluate_command(eval);
    if (generatec->parsed()) return datasets_command(datasets);
  } catch (const dampbench::InputError& e) {
    std::fprintf(stderr, "dampbench: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dampbench: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
