// `dampbench fit` and a sweep group are one pipeline (engine/fit): the same request, the same model, records,
// optimizer, budget, seed, runs and random streams, gives the same parameters, metrics and verdict bit for bit
// through either entry point. The entry points name a task differently (task_key), so the streams of a request
// are named by its task key: the sweep's key given to the fit request must reproduce the group, and the fit's own
// key must reproduce what the command prints.
#include "engine/fit/prepared_fit.hpp"
#include "engine/fit/record_start.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/record/record_options.hpp"
#include "engine/sweep/plan.hpp"
#include "engine/sweep/runner.hpp"
#include "engine/sweep/spec.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

namespace fs = std::filesystem;

/// One request, as `fit` options and as the sweep file that asks for the same fit.
struct Case {
  std::string name, model, laws, optimizer;
  int population = 20, iterations = 20, runs = 2;
  std::uint64_t seed = 7;
  std::vector<std::string> paths;
  RecordOptions data;
  std::string metric = "of_abs";
  std::string start;  ///< "" or "per-file" (`fit --start`, a sweep model's `start`)
};

std::string utfsm(const std::string& file) {
  return (fs::path(DAMPBENCH_SHARED_DATA_DIR) / "utfsm-mr-damper" / file).string();
}

RecordOptions utfsm_options() {
  RecordOptions o;
  o.columns = "t,x,v,F";
  o.units = "x=mm,v=mm/s";
  o.conditions = "utfsm";
  return o;
}

std::vector<Case> cases() {
  const std::string fvd = std::string(DAMPBENCH_SOURCE_DIR) + "/datasets/fvd/";
  std::vector<Case> c;
  c.push_back({"fvd_pso", "fvd.gv_linear_elastic", "", "pso", 20, 20, 2, 7, {fvd + "test1_20mm_92mms.csv"}, {}, "of_abs", ""});
  c.push_back({"fvd_joint_de", "fvd.generalized_viscous", "", "de", 16, 12, 3, 3,
               {fvd + "test2_20mm_230mms.csv", fvd + "test3_20mm_460mms.csv"}, {}, "nrmse", ""});
  c.push_back({"bouc_wen_ga_lm", "mrd.bouc_wen", "", "ga-lm", 12, 4, 2, 1, {utfsm("10mm1Hz1A.txt")}, utfsm_options(),
               "nrmse", ""});
  c.push_back({"bingham_laws_joint", "mrd.bingham", "f_c=poly(I,1);c0=poly(I,1)", "pso", 20, 15, 2, 5,
               {utfsm("10mm1Hz0A.txt"), utfsm("10mm1Hz1A.txt")}, utfsm_options(), "nrmse", ""});
  c.push_back({"bingham_laws_start_per_file", "mrd.bingham", "f_c=poly(I,1);c0=poly(I,1)", "pso", 20, 15, 2, 5,
               {utfsm("10mm1Hz0A.txt"), utfsm("10mm1Hz0x5A.txt"), utfsm("10mm1Hz1A.txt")}, utfsm_options(), "nrmse",
               "per-file"});
  return c;
}

FitSpec fit_spec(const Case& c) {
  FitSpec s;
  s.model.model = c.model;
  s.model.laws = c.laws;
  s.model.option_prefix = "--";
  s.paths = c.paths;
  s.data = c.data;
  s.metric = c.metric;
  s.optimizer = c.optimizer;
  s.population = c.population;
  s.iterations = c.iterations;
  s.runs = c.runs;
  s.seed = c.seed;
  s.start = c.start;
  return s;
}

/// The request `fit` runs: with `--start per-file`, started from the laws fitted to its records' own fits.
FitRequest started_request(const PreparedFit& prepared) {
  FitRequest request = prepared.request();
  seed_from_record_fits(prepared, request, nullptr, {});
  return request;
}

/// The sweep file of the same fit: one model, one optimizer, the records fitted together in one group.
std::string sweep_text(const Case& c) {
  std::string t = fmt::format("name = \"same_fit\"\nseed = {}\nruns = {}\nmetric = \"{}\"\n", c.seed, c.runs, c.metric);
  if (c.laws.empty()) t += fmt::format("models = [\"{}\"]\n", c.model);
  else t += fmt::format("[[models]]\nname = \"{}\"\nmodel = \"{}\"\nlaws = \"{}\"\n", c.model, c.model, c.laws);
  if (!c.start.empty()) t += fmt::format("start = \"{}\"\n", c.start);
  t += fmt::format("[optimizer]\nname = \"{}\"\npopulation = {}\niterations = {}\n", c.optimizer, c.population,
                   c.iterations);
  for (std::size_t i = 0; i < c.paths.size(); ++i) {
    // Named as `fit` names the record (its file's stem): the per-record fits of a start are keyed by record name.
    t += fmt::format("[[datasets]]\nname = \"{}\"\nfile = \"{}\"\n", fs::path(c.paths[i]).stem().string(), c.paths[i]);
    if (!c.data.columns.empty()) t += fmt::format("columns = \"{}\"\n", c.data.columns);
    if (!c.data.units.empty()) t += fmt::format("units = \"{}\"\n", c.data.units);
    if (!c.data.conditions.empty()) t += fmt::format("conditions = \"{}\"\n", c.data.conditions);
  }
  t += "[[splits]]\nname = \"joint\"\nby = \"all\"\n";
  return t;
}

bool data_present(const Case& c) {
  for (const auto& p : c.paths)
    if (!fs::exists(p)) return false;
  return true;
}

using testing::bits;

void expect_same_bits(const std::vector<double>& a, const std::vector<double>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(bits(a[i]), bits(b[i])) << what << "[" << i << "]";
}

class FitPipeline : public ::testing::TestWithParam<Case> {};

TEST_P(FitPipeline, FitAndSweepGroupGiveTheSameBits) {
  const Case& c = GetParam();
  if (!data_present(c)) GTEST_SKIP() << "records absent: " << c.paths.front();
  const fs::path dir = testing::test_temp_dir("fit_pipeline_" + c.name);
  const std::string path = (dir / "same_fit.toml").string();
  std::ofstream(path) << sweep_text(c);
  const sweep::Plan plan(sweep::load_sweep(path), [](const RecordOptions& o) { return load_record(o, true); });
  ASSERT_EQ(plan.groups(), 1);
  const sweep::GroupRecord group = sweep::run_group(plan, 0);
  ASSERT_FALSE(group.failed) << group.message;

  const PreparedFit prepared = prepare_fit(fit_spec(c));
  FitRequest request = started_request(prepared);
  request.settings.task_key = group.task_key;  // the group's streams
  const FitOutcome fit = run_fit(request);

  ASSERT_EQ(fit.identification.runs.size(), group.run_results.size());
  for (std::size_t r = 0; r < group.run_results.size(); ++r) {
    const RunResult& a = fit.identification.runs[r];
    const sweep::RunRecord& b = group.run_results[r];
    const std::string run = fmt::format("run {} ", r);
    expect_same_bits(a.best_params, b.params, run + "parameters");
    EXPECT_EQ(bits(a.best_value), bits(b.best_value)) << run;
    expect_same_bits({a.best_metrics.begin(), a.best_metrics.end()}, {b.metrics.begin(), b.metrics.end()}, run + "metrics");
    EXPECT_EQ(a.evaluations, b.evaluations) << run;
    EXPECT_EQ(a.stop_reason, b.stop_reason) << run;
    const std::vector<TracePoint> trace = improvement_points(a);
    ASSERT_EQ(trace.size(), b.trace.size()) << run;
    for (std::size_t k = 0; k < trace.size(); ++k) {
      EXPECT_EQ(trace[k].evaluations, b.trace[k].evaluations) << run << "trace " << k;
      EXPECT_EQ(bits(trace[k].value), bits(b.trace[k].value)) << run << "trace " << k;
    }
  }
  // The verdict the sweep's tables give from the stored runs is the one `fit` prints.
  std::vector<RunHistory> histories;
  for (const auto& r : group.run_results) histories.push_back({r.best_value, r.trace, r.at_local_optimum});
  const Convergence stored = assess_convergence(histories);
  EXPECT_EQ(stored.verdict(), fit.convergence.verdict());
  EXPECT_EQ(stored.converged, fit.convergence.converged);
  EXPECT_EQ(bits(stored.median_above_best_rel), bits(fit.convergence.median_above_best_rel));
  EXPECT_EQ(bits(stored.late_gain_rel), bits(fit.convergence.late_gain_rel));
  ASSERT_TRUE(group.identifiability.has_value());
  ASSERT_TRUE(fit.identifiability.has_value());
  expect_same_bits(group.identifiability->std_error, fit.identifiability->std_error, "std. errors");
  expect_same_bits(group.identifiability->relative_error, fit.identifiability->relative_error, "relative errors");
  EXPECT_EQ(group.identifiability->flags, fit.identifiability->flags);

  // The streams are the request's: the fit's own key gives other runs (the comparison above could fail).
  const FitOutcome own = run_fit(started_request(prepared));
  EXPECT_NE(bits(own.identification.runs[0].best_params[0]), bits(fit.identification.runs[0].best_params[0]));
}

TEST_P(FitPipeline, CommandPrintsTheRequestOutcome) {
  const Case& c = GetParam();
  if (!data_present(c)) GTEST_SKIP() << "records absent: " << c.paths.front();
  std::string args = fmt::format("fit --format json --model {} --optimizer {} --pop {} --iters {} --runs {} --seed {} "
                                 "--metric {}",
                                 c.model, c.optimizer, c.population, c.iterations, c.runs, c.seed, c.metric);
  if (!c.laws.empty()) args += " --laws '" + c.laws + "'";
  if (!c.start.empty()) args += " --start " + c.start;
  for (const auto& p : c.paths) args += " --data " + p;
  if (!c.data.columns.empty()) args += " --columns " + c.data.columns + " --units " + c.data.units + " --conditions utfsm";
  const auto printed = testing::run_dampbench(args);
  ASSERT_EQ(printed.exit_code, 0) << printed.output;
  const auto j = nlohmann::json::parse(printed.output.substr(printed.output.find('{')));

  const PreparedFit prepared = prepare_fit(fit_spec(c));
  const FitOutcome fit = run_fit(started_request(prepared));
  const Model& model = *prepared.model.model;
  const RunResult& best = fit.best();
  for (int i = 0; i < model.dim(); ++i)
    EXPECT_EQ(bits(j.at("best_params").at(model.parameters()[i].name).get<double>()), bits(best.best_params[i]))
        << model.parameters()[i].name;
  for (int m = 0; m < kMetricCount; ++m) {
    const auto& v = j.at("metrics").at(std::string(metric_name(kAllMetrics[m])));
    if (v.is_null()) {
      EXPECT_FALSE(std::isfinite(best.best_metrics[m])) << metric_name(kAllMetrics[m]);
    } else {
      EXPECT_EQ(bits(v.get<double>()), bits(best.best_metrics[m])) << metric_name(kAllMetrics[m]);
    }
  }
  EXPECT_EQ(j.at("convergence").at("verdict").get<std::string>(), fit.convergence.verdict());
  EXPECT_EQ(j.at("identifiability").at("identifiable").get<bool>(), fit.identifiability->all_identifiable());
}

INSTANTIATE_TEST_SUITE_P(Requests, FitPipeline, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& param) { return param.param.name; });

}  // namespace
}  // namespace dampbench
