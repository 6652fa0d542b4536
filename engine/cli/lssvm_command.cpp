// `dampbench lssvm`: LS-SVM damper model (lssvm paper; engine/lssvm/lssvm.hpp). Trains on --train records,
// tunes (c, σ) by GA unless both are given, and reports one-step-ahead and free-run metrics on --test records.
#include "engine/cli/lssvm_command.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tbb/parallel_for.h>

#include "engine/cli/cli_options.hpp"
#include "engine/cli/lssvm_reproduction.hpp"
#include "engine/common/error.hpp"
#include "engine/common/table.hpp"
#include "engine/common/text_file.hpp"
#include "engine/fit/lssvm_model_file.hpp"
#include "engine/lssvm/lssvm.hpp"

namespace dampbench::cli {
namespace {

/// Without --max-train, at most this many training samples, evenly spaced over the records, with a note in the
/// output, so that a command over many long records finishes without a flag. The kernel matrix is N² doubles and
/// each decomposition O(N³): GA tuning (50 × 500) at 2 000 samples takes about a minute on two cores, at 5 000
/// it would take some fifteen.
constexpr int kDefaultMaxTrain = 2000;
/// With --max-train 0 (all), more samples than this are refused: 20 000² doubles are 3.2 GB.
constexpr int kMaxTrainAll = 20000;

nlohmann::ordered_json metrics_json(const lssvm::ErrorMetrics& m) {
  return {{"mse", json_number(m.mse)},         {"mae", json_number(m.mae)},     {"max_abs", json_number(m.max_abs)},
          {"max_rel", json_number(m.max_rel)}, {"nrmse", json_number(m.nrmse)}, {"samples", m.samples}};
}

std::vector<std::string> metric_cells(const lssvm::ErrorMetrics& m) {
  return {format_number(m.mse), format_number(m.mae), format_number(m.max_abs), format_number(m.max_rel),
          format_number(m.nrmse)};
}

std::vector<Dataset> load_files(const std::vector<std::string>& paths, const RecordOptions& data) {
  std::vector<Dataset> records;
  for (const std::string& path : paths) {
    RecordOptions d = data;
    d.path = path;
    for (Dataset& record : load_records(d, false)) records.push_back(std::move(record));
  }
  return records;
}

}  // namespace

void add_lssvm_options(CLI::App* cmd, LssvmOptions& o) {
  cmd->add_option("--train", o.train, "training record (repeat for several)")->required();
  cmd->add_option("--test", o.test, "test record (repeat for several)")->required();
  cmd->add_option("--lags", o.lags, "lag orders d=N,v=N,y=N (default d=2,v=2,y=2)");
  cmd->add_option("--max-train", o.max_train,
                  fmt::format("at most N training samples, evenly spaced over the records (default {}; 0: all, up to {})",
                              kDefaultMaxTrain, kMaxTrainAll));
  cmd->add_option("--seed", o.seed, "GA seed (default 1)");
  cmd->add_option("--fitness", o.fitness,
                  "validation (default: one-step MSE on the held-out tail of each training record), free-run (MSE "
                  "of the model's own simulation of those tails, what a controller uses) or paper (eq. 8: training SSE)");
  cmd->add_option("--validation", o.validation, "held-out fraction of each training record (default 0.2)");
  cmd->add_option("--pop", o.population, "GA population (default 50, paper; PSO swarm of 16 for --fitness free-run)");
  cmd->add_option("--generations", o.generations, "GA generations (default 500, paper; PSO iterations 16 for --fitness free-run)");
  cmd->add_option("--c", o.c, "fixed c (with --sigma): no GA");
  cmd->add_option("--sigma", o.sigma, "fixed sigma (with --c): no GA");
  cmd->add_option("--format", o.format, "md (default) or json");
  cmd->add_option("-o,--output", o.output,
                  "folder for errors.csv (each test sample's forces and errors) and convergence.csv (the search's best "
                  "objective per generation)");
  cmd->add_option("--reproduce", o.reproduce,
                  "the lssvm paper's numbers (datasets/papers/lssvm.toml): write reproduction.md and reproduction.json, "
                  "ours beside them with verdicts, into the -o folder");
  cmd->add_option("--truth", o.truth,
                  "with --reproduce: the records are synthetic, made from this (e.g. \"mrd.bouc_wen, datasets/lssvm\"); "
                  "without it they are real");
  cmd->add_option("--save-model", o.save_model,
                  "also write the trained model as JSON (for evaluate/simulate --model-file; its test predictions the same bits)");
  add_data_options(cmd, o.data);
}

namespace {

/// The GA (or, for the free-run fitness, PSO) settings the options ask for.
lssvm::TuneSettings tune_settings(const LssvmOptions& o) {
  lssvm::TuneSettings settings;
  settings.fitness = lssvm::parse_fitness(o.fitness);
  settings.validation_fraction = o.validation;
  // A free-run candidate costs a kernel matrix and a Cholesky solve (~0.2 s at 2 000 rows), where the validation
  // fitness shares eigendecompositions: PSO 16 × 16 = 256 evaluations (engine/lssvm/tuning.cpp).
  const bool tune_free_run = settings.fitness == lssvm::Fitness::free_run;
  settings.population = o.population.value_or(tune_free_run ? 16 : 50);
  settings.generations = o.generations.value_or(tune_free_run ? 16 : 500);
  settings.seed = o.seed;
  return settings;
}

/// The records the current is missing from (taken as 0 A, lssvm.hpp); InputError or DataError for test records
/// that cannot be predicted.
std::vector<std::string> check_records(const std::vector<Dataset>& train, const std::vector<Dataset>& test,
                                       const lssvm::Lags& lags) {
  std::vector<std::string> without_current;
  for (const auto* records : {&train, &test})
    for (const Dataset& r : *records)
      if (!r.operating.contains("I")) without_current.push_back(r.source.empty() ? r.name : r.source);
  for (const Dataset& r : test)
    if (!r.has_force())
      throw DataError(fmt::format("lssvm: test record '{}' has no force (F column); it is needed for one-step "
                                   "prediction and the metrics",
                                   r.source.empty() ? r.name : r.source));
  for (const Dataset& r : test)
    if (r.size() < static_cast<std::size_t>(lags.first()) + 1)
      throw InputError(fmt::format("lssvm: test record '{}' has {} samples; lags {} need at least {}", r.name, r.size(),
                                   lssvm::format_lags(lags), lags.first() + 1));
  return without_current;
}

/// The training rows, at most --max-train of them (the default cap without it), and the note that says so.
lssvm::TrainingRows training_rows(const std::vector<Dataset>& train, const lssvm::Lags& lags, const LssvmOptions& o,
                                  std::string& subsampled) {
  const int cap = o.max_train.value_or(kDefaultMaxTrain);  // build_rows rejects a negative one
  lssvm::TrainingRows rows = lssvm::build_rows(train, lags, cap);
  if (cap == 0 && rows.size() > kMaxTrainAll)
    throw InputError(fmt::format("lssvm: {} training samples; the kernel matrix would take {:.1f} GB and each "
                                 "solve O(N³): pass --max-train N (the paper used 1260; default {})",
                                 rows.size(), 8.0 * rows.size() * rows.size() / 1e9, kDefaultMaxTrain));
  // Said in the output whenever rows were dropped.
  subsampled =
      rows.size() < rows.available
          ? fmt::format(" of {} (evenly spaced: {}; --max-train N to change, 0 for all)", rows.available,
                        o.max_train ? "--max-train" : fmt::format("the default cap of {} without --max-train", kDefaultMaxTrain))
          : "";
  return rows;
}

struct TestResults {
  std::vector<LssvmRecordErrors> records;
  lssvm::ErrorMetrics one_step, free_run;  ///< pooled over every test record
  std::vector<std::vector<double>> one_step_forces, free_run_forces;  ///< per test record, every sample
};

/// One-step and free-run predictions of every test record, in parallel; metrics pooled afterwards in record order
/// (same bits for any thread count).
TestResults test_model(const lssvm::Model& model, const std::vector<Dataset>& test, const lssvm::Lags& lags) {
  const std::size_t from = static_cast<std::size_t>(lags.first());
  std::vector<std::vector<double>> one_pred(test.size()), free_pred(test.size());
  tbb::parallel_for(std::size_t{0}, test.size(), [&](std::size_t k) {
    one_pred[k] = model.predict_one_step(test[k]);
    free_pred[k] = model.simulate(test[k]);
  });
  TestResults out;
  lssvm::MetricAccumulator all_one, all_free;
  for (std::size_t k = 0; k < test.size(); ++k) {
    lssvm::MetricAccumulator one, free;
    one.add(test[k].F_N, one_pred[k], from);
    free.add(test[k].F_N, free_pred[k], from);
    out.records.push_back({test[k].name, one.finish(), free.finish()});
    all_one.add(test[k].F_N, one_pred[k], from);
    all_free.add(test[k].F_N, free_pred[k], from);
  }
  out.one_step = all_one.finish();
  out.free_run = all_free.finish();
  out.one_step_forces = std::move(one_pred);
  out.free_run_forces = std::move(free_pred);
  return out;
}

/// -o DIR: the per-sample forces and errors of every test record (the paper's Fig. 7 shows per-sample errors) and,
/// when tuned, the search's best objective per generation (its Fig. 8, the convergence of eq. 8's fitness).
void write_outputs(const std::string& dir, const std::vector<Dataset>& test, const TestResults& results,
                   const lssvm::TuneResult& tuned, bool fixed) {
  std::string errors = "record,t,F_measured,F_one_step,F_free_run,e_one_step,e_free_run\n";
  for (std::size_t k = 0; k < test.size(); ++k)
    for (std::size_t i = 0; i < test[k].size(); ++i) {
      const double F = test[k].F_N[i], one = results.one_step_forces[k][i], free = results.free_run_forces[k][i];
      errors += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", test[k].name, test[k].t_s[i], F, one,
                            free, F - one, F - free);
    }
  write_text_file((std::filesystem::path(dir) / "errors.csv").string(), errors);
  if (fixed) return;
  std::string convergence = "generation,best_objective\n";
  for (std::size_t g = 0; g < tuned.best_history.size(); ++g)
    convergence += fmt::format("{},{:.17g}\n", g + 1, tuned.best_history[g]);
  write_text_file((std::filesystem::path(dir) / "convergence.csv").string(), convergence);
}

/// Everything the output shows besides the test metrics.
struct LssvmRun {
  const lssvm::TuneSettings& settings;
  const lssvm::TuneResult& tuned;
  bool fixed = false;
  double seconds = 0;
  const lssvm::Lags& lags;
  const lssvm::TrainingRows& rows;
  std::size_t train_records = 0, test_records = 0;
  const std::vector<std::string>& without_current;
  const std::string& subsampled;
  const sweep::Reproduction* reproduction = nullptr;  ///< with --reproduce
  std::string reproduction_dir = {};
};

/// The run's figures the paper's numbers stand beside (lssvm_reproduction.hpp).
LssvmRunFigures run_figures(const std::vector<Dataset>& train, const lssvm::TrainingRows& rows,
                            const lssvm::TuneResult& tuned, const TestResults& results) {
  LssvmRunFigures figures{static_cast<std::size_t>(rows.size()), tuned.c, tuned.sigma, {}, results.records, {"all", results.one_step, results.free_run}};
  for (const Dataset& record : train) figures.trained_on.push_back(record.name);
  return figures;
}

void print_json(const LssvmRun& run, const TestResults& results) {
  const lssvm::TuneResult& tuned = run.tuned;
  nlohmann::ordered_json j;
  j["c"] = tuned.c;
  j["sigma"] = tuned.sigma;
  j["tuned"] = !run.fixed;
  j["fitness"] = std::string(lssvm::fitness_name(run.settings.fitness));
  if (!run.fixed) {
    j["objective"] = json_number(tuned.objective);
    if (run.settings.fitness == lssvm::Fitness::paper) j["paper_fitness"] = json_number(1.0 / (tuned.objective + 1e-6));
    j["factorizations"] = tuned.factorizations;
    j["evaluations"] = tuned.evaluations;
    j["fit_samples"] = tuned.fit_rows;
    j["validation_samples"] = tuned.validation_rows;
    if (run.settings.fitness == lssvm::Fitness::free_run) j["free_run_samples"] = tuned.free_run_samples;
  }
  j["lags"] = {{"d", run.lags.d}, {"v", run.lags.v}, {"y", run.lags.y}};
  j["train_samples"] = run.rows.size();
  j["train_samples_available"] = run.rows.available;
  j["records_without_current"] = run.without_current;
  j["one_step"] = metrics_json(results.one_step);
  j["free_run"] = metrics_json(results.free_run);
  nlohmann::ordered_json recs = nlohmann::ordered_json::array();
  for (const LssvmRecordErrors& r : results.records)
    recs.push_back({{"name", r.name}, {"one_step", metrics_json(r.one_step)}, {"free_run", metrics_json(r.free_run)}});
  j["records"] = recs;
  if (run.reproduction) {
    nlohmann::ordered_json items = nlohmann::ordered_json::array();
    for (const sweep::ReproductionItem& item : run.reproduction->items)
      items.push_back({{"id", item.id}, {"verdict", item.verdict}});
    j["reproduction"] = {{"folder", run.reproduction_dir}, {"items", items}};
  }
  std::cout << j.dump(2) << "\n";
}

/// The tuning's lines of the Markdown output: fitness, search and its cost.
void print_tuning(const LssvmRun& run) {
  const lssvm::TuneSettings& settings = run.settings;
  const lssvm::TuneResult& tuned = run.tuned;
  const bool tune_free_run = settings.fitness == lssvm::Fitness::free_run;
  if (settings.fitness == lssvm::Fitness::validation)
    std::cout << fmt::format("- fitness: validation, one-step MSE on the last {:g} % of each training record "
                             "({} fitted + {} held out)\n",
                             100 * settings.validation_fraction, tuned.fit_rows, tuned.validation_rows);
  else if (tune_free_run)
    std::cout << fmt::format("- fitness: free run, MSE of the model's own simulation of the last {:g} % of each "
                             "training record ({} fitted rows; {} samples simulated from each record's first "
                             "held-out sample)\n",
                             100 * settings.validation_fraction, tuned.fit_rows, tuned.free_run_samples);
  else
    std::cout << fmt::format("- fitness: paper eq. 8, 1/(training SSE + 1e-6) = {} on {} samples\n",
                             format_number(1.0 / (tuned.objective + 1e-6)), tuned.fit_rows);
  if (tune_free_run)
    std::cout << fmt::format(
        "- PSO over log10 c and log10 sigma: {} particles, {} iterations; c in [{:g}, {:g}], sigma in [{:g}, {:g}] "
        "(grid of {} per decade); {} evaluations (one Cholesky solve each), {:.1f} s\n",
        settings.population, settings.generations, settings.c_min, settings.c_max, settings.sigma_min,
        settings.sigma_max, settings.sigma_per_decade, tuned.evaluations, run.seconds);
  else
    std::cout << fmt::format(
        "- GA: population {}, {} generations, pc {:g}, pm {:g}; c in [{:g}, {:g}], sigma in [{:g}, {:g}] "
        "(grid of {} per decade); {} evaluations, {} eigendecompositions, {:.1f} s\n",
        settings.population, settings.generations, settings.pc, settings.pm, settings.c_min, settings.c_max,
        settings.sigma_min, settings.sigma_max, settings.sigma_per_decade, tuned.evaluations, tuned.factorizations,
        run.seconds);
}

void print_markdown(const LssvmRun& run, const TestResults& results) {
  std::cout << "# LS-SVM damper model (lssvm paper)\n\n";
  std::cout << fmt::format("- training: {} records, {} samples{}; lags {} ({} inputs)\n", run.train_records,
                           run.rows.size(), run.subsampled, lssvm::format_lags(run.lags), run.lags.dim());
  if (!run.without_current.empty()) {
    std::string names;
    for (const std::string& n : run.without_current) names += (names.empty() ? "" : ", ") + n;
    std::cout << fmt::format("- current: {} of {} records have no operating variable I and are taken as 0 A (give it "
                             "with --set I=..., --conditions utfsm, a column or a '# operating:' line): {}\n",
                             run.without_current.size(), run.train_records + run.test_records, names);
  }
  if (run.fixed) std::cout << "- hyperparameters given (no GA)\n";
  else print_tuning(run);
  std::cout << fmt::format("- c = {}, sigma = {}{}\n\n", format_number(run.tuned.c), format_number(run.tuned.sigma),
                           run.fixed ? "" : fmt::format(" (objective {} N²)", format_number(run.tuned.objective)));
  Table t{"lssvm_test", "Test metrics: one-step-ahead | free run (e = F_measured − F_model; max rel = max abs / max abs F)",
          {"record", "samples", "1-step MSE [N²]", "MAE [N]", "max abs [N]", "max rel", "nrmse", "free MSE [N²]",
           "MAE [N]", "max abs [N]", "max rel", "nrmse"},
          {}};
  auto row = [&](const std::string& name, const lssvm::ErrorMetrics& a, const lssvm::ErrorMetrics& b) {
    std::vector<Cell> cells{name, std::to_string(a.samples)};
    for (auto& c : metric_cells(a)) cells.push_back(c);
    for (auto& c : metric_cells(b)) cells.push_back(c);
    t.rows.push_back(cells);
  };
  for (const LssvmRecordErrors& r : results.records) row(r.name, r.one_step, r.free_run);
  if (results.records.size() > 1) row("all", results.one_step, results.free_run);
  std::cout << t.to_markdown() << "\n";
  if (!run.reproduction) return;
  std::cout << fmt::format("Against the lssvm paper's numbers ({}/reproduction.md, with ours beside each):\n\n"
                           "| item | verdict | detail |\n|---|---|---|\n",
                           run.reproduction_dir);
  for (const sweep::ReproductionItem& item : run.reproduction->items)
    std::cout << fmt::format("| {} | **{}** | {} |\n", item.id, item.verdict, item.detail);
  std::cout << "\n";
}

}  // namespace

int lssvm_command(const LssvmOptions& o) {
  if (o.format != "md" && o.format != "json")
    throw InputError(fmt::format("--format: expected md or json, got '{}'", o.format));
  const lssvm::Lags lags = lssvm::parse_lags(o.lags);
  const lssvm::TuneSettings settings = tune_settings(o);
  const bool fixed = !std::isnan(o.c) || !std::isnan(o.sigma);
  if (fixed && (std::isnan(o.c) || std::isnan(o.sigma)))
    throw InputError("lssvm: give both --c and --sigma (fixed hyperparameters) or neither (GA tuning)");
  if (o.train.empty()) throw InputError("lssvm: empty training set (no --train records)");
  if (o.test.empty()) throw InputError("lssvm: no --test records");
  check_output_folder("--save-model", o.save_model);  // before the training, not after it
  if (!o.reproduce.empty() && o.output.empty())
    throw InputError("--reproduce: give -o FOLDER, where reproduction.md and reproduction.json go");
  if (!o.truth.empty() && o.reproduce.empty())
    throw InputError("--truth: it describes the records of a reproduction; give --reproduce FILE too");
  if (!o.reproduce.empty()) check_lssvm_paper_file(o.reproduce);
  if (!o.output.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.output, ec);
    if (ec || !std::filesystem::is_directory(o.output))
      throw InputError(fmt::format("-o: cannot make the folder '{}'", o.output));
  }

  const std::vector<Dataset> train = load_files(o.train, o.data);
  const std::vector<Dataset> test = load_files(o.test, o.data);
  // The current is a regressor input; a record without one is taken as 0 A (lssvm.hpp), and the output says so.
  const std::vector<std::string> without_current = check_records(train, test, lags);
  std::string subsampled;
  const lssvm::TrainingRows rows = training_rows(train, lags, o, subsampled);

  lssvm::TuneResult tuned;
  double seconds = 0;
  if (fixed) {
    tuned.c = o.c;
    tuned.sigma = o.sigma;
  } else {
    const auto start = std::chrono::steady_clock::now();
    tuned = lssvm::tune(rows, settings, {train, lags});
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  const lssvm::Model model = lssvm::Model::train(rows, lags, tuned.c, tuned.sigma);
  if (!o.save_model.empty()) {
    std::vector<std::string> trained_on;
    for (const Dataset& record : train) trained_on.push_back(record.name);
    write_lssvm_model_file(o.save_model, model, trained_on, DAMPBENCH_VERSION);
  }
  const TestResults results = test_model(model, test, lags);
  if (!o.output.empty()) write_outputs(o.output, test, results, tuned, fixed);
  LssvmRun run{settings, tuned, fixed, seconds, lags, rows, train.size(), test.size(), without_current, subsampled};
  std::optional<sweep::Reproduction> reproduction;
  if (!o.reproduce.empty()) {
    reproduction = write_lssvm_reproduction(o.output, o.reproduce, o.truth, run_figures(train, rows, tuned, results));
    run.reproduction = &*reproduction;
    run.reproduction_dir = o.output;
  }
  if (o.format == "json") print_json(run, results);
  else print_markdown(run, results);
  return 0;
}

}  // namespace dampbench::cli
