// Held-out evaluation (engine/fit/held_out): folds by rule on known records, a prediction is `evaluate`'s metric,
// and `fit --predict/--folds/--reference` end to end on records simulated from a known law, where the true law
// predicts a held-out current at the noise floor and a wrong one cannot.
#include "engine/fit/held_out.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/fit/fit_records.hpp"
#include "engine/fit/fitted_range.hpp"
#include "engine/fit/law_selection.hpp"
#include "engine/model/law_model.hpp"
#include "engine/model/parameter_law.hpp"
#include "engine/record/excitation.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

namespace fs = std::filesystem;

using testing::bits;

/// A short sine record named `name` with the given operating variables.
Signals record(const std::string& name, const std::map<std::string, double>& operating, double amp = 0.01,
               double freq = 1) {
  Signals s = testing::sine_signals(amp, freq, 1, 400, operating);
  s.name = name;
  return s;
}

std::vector<const Signals*> pointers(const std::vector<Signals>& records) {
  std::vector<const Signals*> p;
  for (const Signals& s : records) p.push_back(&s);
  return p;
}

void expect_fold(const Fold& f, const std::string& name, const std::vector<int>& fit, const std::vector<int>& predict) {
  EXPECT_EQ(f.name, name);
  EXPECT_EQ(f.fit, fit) << name;
  EXPECT_EQ(f.predict, predict) << name;
}

TEST(HeldOut, LeaveOneValueOutSortsTheValuesAndMergesNearEqualOnes) {
  // Out of order, and 0.5 twice: once exactly and once 1e-12 relative above (the same value read from two files).
  const std::vector<Signals> r{record("a", {{"I", 1.0}}), record("b", {{"I", 0.5}}), record("c", {{"I", 0.0}}),
                               record("d", {{"I", 0.5 * (1 + 1e-12)}})};
  const std::vector<Fold> folds = make_folds(pointers(r), "leave-one:I", "--folds");
  ASSERT_EQ(folds.size(), 3u);
  expect_fold(folds[0], "I=0", {0, 1, 3}, {2});
  expect_fold(folds[1], "I=0.5", {0, 2}, {1, 3});
  expect_fold(folds[2], "I=1", {1, 2, 3}, {0});
  // A value 1e-6 relative apart is another value.
  const std::vector<Signals> apart{record("a", {{"I", 0.5}}), record("b", {{"I", 0.5 * (1 + 1e-6)}})};
  EXPECT_EQ(make_folds(pointers(apart), "leave-one:I", "--folds").size(), 2u);
}

TEST(HeldOut, LeaveSettingOutGroupsAmplitudeAndFrequency) {
  // Stated settings, sorted by amplitude, then frequency; the currents do not split a setting.
  const std::vector<Signals> r{record("a", {{"I", 0.0}, {"amp", 0.025}, {"freq", 0.5}}),
                               record("b", {{"I", 0.0}, {"amp", 0.01}, {"freq", 1.0}}),
                               record("c", {{"I", 1.0}, {"amp", 0.025}, {"freq", 0.1}}),
                               record("d", {{"I", 1.0}, {"amp", 0.01}, {"freq", 1.0}}),
                               record("e", {{"I", 0.5}, {"amp", 0.025}, {"freq", 0.5}})};
  const std::vector<Fold> folds = make_folds(pointers(r), "leave-setting", "--folds");
  ASSERT_EQ(folds.size(), 3u);
  expect_fold(folds[0], "amp=0.01,freq=1", {0, 2, 4}, {1, 3});
  expect_fold(folds[1], "amp=0.025,freq=0.1", {0, 1, 3, 4}, {2});
  expect_fold(folds[2], "amp=0.025,freq=0.5", {1, 2, 3}, {0, 4});
  // Without stated settings amp and freq come from the records themselves (half the stroke, eq. 15's frequency).
  const std::vector<Signals> estimated{record("x", {}, 0.01, 1), record("y", {}, 0.02, 2), record("z", {}, 0.01, 1)};
  const std::vector<Fold> e = make_folds(pointers(estimated), "leave-setting", "--folds");
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].predict, (std::vector<int>{0, 2}));
  EXPECT_EQ(e[1].predict, (std::vector<int>{1}));
  EXPECT_NEAR(estimated[1].law_variables.at("amp"), 0.02, 1e-12);
}

TEST(HeldOut, BadFoldRulesAreReported) {
  const std::vector<Signals> r{record("a", {{"I", 0.0}}), record("b", {{"I", 1.0}})};
  const auto p = pointers(r);
  EXPECT_EQ(testing::error_of([&] { make_folds(p, "leave-two:I", "--folds"); }),
            "--folds: unknown fold rule 'leave-two:I' (expected leave-one:VAR, e.g. leave-one:I, or leave-setting)");
  EXPECT_EQ(testing::error_of([&] { make_folds(p, "leave-one:", "--folds"); }),
            "--folds: unknown fold rule 'leave-one:' (expected leave-one:VAR, e.g. leave-one:I, or leave-setting)");
  EXPECT_EQ(testing::error_of([&] { make_folds(p, "leave-one:V", "--folds"); }),
            "--folds leave-one:V: record 'a' has no operating variable 'V' (give it with --set V=... or in the record)");
  const std::vector<Signals> same{record("a", {{"I", 0.5}}), record("b", {{"I", 0.5}})};
  EXPECT_EQ(testing::error_of([&] { make_folds(pointers(same), "leave-one:I", "--folds"); }),
            "--folds leave-one:I: the 2 records give 1 fold (every record has I=0.5); held-out evaluation needs at "
            "least two");
  EXPECT_EQ(testing::error_of([&] { make_folds({}, "leave-setting", "sweep 'x'"); }),
            "sweep 'x' leave-setting: the 0 records give 0 folds (no records); held-out evaluation needs at least two");
}

TEST(HeldOut, FoldRequestFitsTheFoldsRecordsWithItsOwnStreams) {
  const std::vector<Signals> r{record("a", {{"I", 0.0}}), record("b", {{"I", 0.5}}), record("c", {{"I", 1.0}})};
  FitRequest request;
  request.records = pointers(r);
  request.settings.task_key = 42;
  request.settings.runs = 3;
  const std::vector<Fold> folds = make_folds(request.records, "leave-one:I", "--folds");
  const FitRequest f0 = fold_request(request, folds[0]), f1 = fold_request(request, folds[1]);
  EXPECT_EQ(f0.records, (std::vector<const Signals*>{&r[1], &r[2]}));
  EXPECT_EQ(f1.records, (std::vector<const Signals*>{&r[0], &r[2]}));
  EXPECT_EQ(f0.settings.runs, 3);
  EXPECT_NE(f0.settings.task_key, request.settings.task_key);
  EXPECT_NE(f0.settings.task_key, f1.settings.task_key);
  EXPECT_EQ(fold_request(request, folds[0]).settings.task_key, f0.settings.task_key);
}

TEST(HeldOut, PerFileModelIsTheLawModelsBase) {
  const Model& spencer = find_model("mrd.spencer");
  const LawModel law(spencer, parse_laws("c0=poly(I,1)", "--laws"));
  EXPECT_EQ(&per_file_model(law), &spencer);
  EXPECT_EQ(&per_file_model(spencer), &spencer);
}

TEST(HeldOut, SummaryGivesMeansTheirRatioAndTheWorstRecord) {
  std::vector<RecordError> e{{"held out", "I=0", "a", 0.2, 0.1, "converged"},
                             {"held out", "I=1", "b", 0.3, 0.2, "converged"},
                             {"held out", "I=1", "c", 0.1, 0.02, "converged"}};
  const ErrorSummary s = summarize_errors(e);
  EXPECT_EQ(s.count, 3);
  EXPECT_DOUBLE_EQ(s.mean, 0.2);
  EXPECT_DOUBLE_EQ(s.mean_per_file, 0.32 / 3);
  EXPECT_DOUBLE_EQ(s.ratio_of_means, 0.6 / 0.32);
  EXPECT_DOUBLE_EQ(s.worst_ratio, 5.0);
  EXPECT_EQ(s.worst_record, "c");
  e[1].per_file.reset();  // one record without a reference: no ratios at all
  const ErrorSummary n = summarize_errors(e);
  EXPECT_DOUBLE_EQ(n.mean, 0.2);
  EXPECT_TRUE(std::isnan(n.mean_per_file) && std::isnan(n.ratio_of_means) && std::isnan(n.worst_ratio));
  EXPECT_EQ(n.worst_record, "");
  EXPECT_TRUE(std::isnan(e[1].ratio()));
}

TEST(HeldOut, SummaryLeavesRecordsWithoutAFiniteMetricOutOfTheMeansAndCountsThem) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<RecordError> e{{"held out", "I=0", "a", 0.2, 0.1, "converged"},
                             {"held out", "I=1", "b", inf, 0.2, "converged"},
                             {"held out", "I=1", "c", nan, 0.02, "converged"},
                             {"held out", "I=1", "d", 0.4, 0.1, "converged"}};
  const ErrorSummary s = summarize_errors(e);
  EXPECT_EQ(s.count, 4);
  EXPECT_EQ(s.failed, 2);
  EXPECT_DOUBLE_EQ(s.mean, 0.3);
  EXPECT_DOUBLE_EQ(s.mean_per_file, 0.1);
  EXPECT_DOUBLE_EQ(s.ratio_of_means, 3.0);
  EXPECT_DOUBLE_EQ(s.worst_ratio, 4.0);
  EXPECT_EQ(s.worst_record, "d");
  const ErrorSummary none = summarize_errors(std::span(e).subspan(1, 2));
  EXPECT_EQ(none.failed, 2);
  EXPECT_TRUE(std::isnan(none.mean) && std::isnan(none.ratio_of_means));
}

/// A sine record at `amp_m` and 5 Hz whose force is 1000·v + 100 N (what record-scaled boxes are scaled by).
Signals forced_record(double amp_m) {
  Dataset d = make_sine(SineSpec{amp_m, 5, 0, 2, 400});
  d.operating = {{"I", 0.0}, {"amp", amp_m}, {"freq", 5.0}};
  d.F_N.resize(d.v_m_s.size());
  for (std::size_t k = 0; k < d.v_m_s.size(); ++k) d.F_N[k] = 1000 * d.v_m_s[k] + 100;
  Signals s = prepare_signals(d);
  s.name = fmt::format("sine_{}m", amp_m);
  return s;
}

TEST(HeldOut, AFailedPredictionNamesTheLawValuesOutsideAPerRecordBox) {
  // Spencer under its gauge with n = 0.011/amp + 2: 7.5 at 2 mm, 2.55 at 20 mm; a per-record fit keeps n in 1–3
  // (the Bouc–Wen rule, whatever the record), and every other parameter sits inside both records' boxes.
  const Model& spencer = find_model("mrd.spencer");
  const LawModel law(spencer, parse_laws("n=power(amp)", "--laws"));
  const Signals small = forced_record(0.002), large = forced_record(0.02);
  const ResolvedModel gauged = gauged_model(spencer);
  const Signals* const a[] = {&small};
  const Signals* const b[] = {&large};
  const Bounds box_small = gauged.bounds_for(a), box_large = gauged.bounds_for(b);
  std::vector<double> c(static_cast<std::size_t>(law.dim()));
  for (int j = 0; j < gauged.model->dim(); ++j) {
    const std::string& name = gauged.model->parameters()[j].name;
    if (name == "n") continue;
    const double lo = std::max(box_small.lower[j], box_large.lower[j]), hi = std::min(box_small.upper[j], box_large.upper[j]);
    ASSERT_LT(lo, hi) << name;
    c[law.parameter_index(name)] = 0.5 * (lo + hi);
  }
  c[law.parameter_index("n_k")] = 0.011;
  c[law.parameter_index("n_p")] = -1;
  c[law.parameter_index("n_c")] = 2;
  const std::string failed = prediction_failure(law, c, small);
  EXPECT_NE(failed.find("amp=0.002"), std::string::npos) << failed;
  EXPECT_NE(failed.find("the laws give a parameter outside a per-record fit's box: n = 7.5 (1 to 3)"), std::string::npos)
      << failed;
  const std::string inside = prediction_failure(law, c, large);
  EXPECT_NE(inside.find("the laws give every parameter inside a per-record fit's box"), std::string::npos) << inside;
  // A model without laws has nothing to name but the fit's parameters.
  EXPECT_NE(prediction_failure(spencer, std::vector<double>(10, 1.0), small).find("the fit's parameters give no finite"),
            std::string::npos);
}

TEST(HeldOut, FittedRangeNamesTheLawVariablesOutsideTheFittedRecords) {
  const LawModel law(find_model("mrd.spencer"), parse_laws("c0=poly(I,1);n=power(amp)", "--laws"));
  const FittedRange range(law, {{{"I", 0.0}, {"amp", 0.025}, {"freq", 1.0}}, {{"I", 1.0}, {"amp", 0.005}, {"freq", 5.0}}});
  EXPECT_EQ(range.outside({{"I", 0.5}, {"amp", 0.002}, {"freq", 9.0}}), "amp = 0.002 (fitted on 0.005 to 0.025)");
  EXPECT_EQ(range.outside({{"I", 3.0}, {"amp", 0.03}}), "I = 3 (fitted on 0 to 1), amp = 0.03 (fitted on 0.005 to 0.025)");
  EXPECT_EQ(range.outside({{"I", 1.0 + 1e-12}, {"amp", 0.005}}), "");  // the ends, read from files, are inside
  // freq is no law's variable here, and a model without laws never extrapolates a law.
  EXPECT_EQ(range.outside({{"I", 0.5}, {"amp", 0.01}, {"freq", 50.0}}), "");
  EXPECT_EQ(FittedRange(find_model("mrd.spencer"), {{{"I", 0.0}}}).outside({{"I", 9.0}}), "");
}

TEST(HeldOut, RecordMetricIsEvaluatesMetric) {
  const std::string file = std::string(DAMPBENCH_SOURCE_DIR) + "/datasets/fvd/test3_20mm_460mms.csv";
  const auto printed = testing::run_dampbench("evaluate --model fvd.gv_linear_elastic --params m=300,C=8e5,alpha=0.3,"
                                              "K1=4e6 --format json --data " + file);
  ASSERT_EQ(printed.exit_code, 0) << printed.output;
  const auto j = nlohmann::json::parse(printed.output).at(file);
  const Model& model = find_model("fvd.gv_linear_elastic");
  const FitRecords records = load_fit_records(model, {file}, {});
  const std::vector<double> params{300, 8e5, 0.3, 4e6};
  for (Metric m : kAllMetrics) {
    const auto& v = j.at(std::string(metric_name(m)));
    ASSERT_FALSE(v.is_null()) << metric_name(m);
    EXPECT_EQ(bits(record_metric(model, params, records.signals[0], m)), bits(v.get<double>())) << metric_name(m);
  }
  EXPECT_EQ(testing::error_of([&] { record_metric(model, std::vector<double>{1.0}, records.signals[0], Metric::rmse); }),
            "fvd.gv_linear_elastic has 4 parameters, got 1");
}

// ---- `fit --predict / --folds / --reference` end to end ------------------------------------------------------

/// Records simulated from a known law model, one CSV per current (its I in an "# operating:" line), optionally
/// with force noise.
class Simulated {
 public:
  Simulated(const std::string& model, const std::string& laws, const std::vector<double>& truth, double noise)
      : dir_(testing::test_temp_dir("held_out")) {
    const LawModel law(find_model(model), parse_laws(laws, "--laws"));
    for (double I : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      SineSpec spec{0.01, 1, 0, 2, 200};
      Dataset d = make_sine(spec);
      d.operating["I"] = I;
      d.F_N = law.simulate(truth, prepare_signals(d));
      if (noise > 0) testing::add_force_noise(d, noise, static_cast<std::uint64_t>(1000 * I) + 11);
      std::ofstream out(file(I));
      out << fmt::format("# operating: I={}\nt[s],x[m],v[m/s],a[m/s^2],F[N]\n", I);
      for (std::size_t k = 0; k < d.t_s.size(); ++k)
        out << fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", d.t_s[k], d.x_m[k], d.v_m_s[k], d.a_m_s2[k],
                           d.F_N[k]);
    }
  }
  [[nodiscard]] std::string file(double I) const { return (dir_ / fmt::format("rec_{}A.csv", I)).string(); }
  /// " --data F0 --data F0.5 --data F1": the three currents the laws are fitted on.
  [[nodiscard]] std::string fitted_on() const {
    return fmt::format(" --data {} --data {} --data {}", file(0), file(0.5), file(1));
  }

 private:
  fs::path dir_;
};

/// The JSON a command prints on stdout; its stderr (progress lines, messages) into `errors` when given.
nlohmann::json run_json(const std::string& args, std::string* errors = nullptr) {
  const auto r = testing::run_dampbench_json(args + " --format json");
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.errors;
  if (errors) *errors = r.errors;
  if (r.exit_code != 0) return nlohmann::json::object();
  return nlohmann::json::parse(r.output);
}

/// The held-out rows of a fit's JSON: record name -> metric.
std::map<std::string, double> held_out_metrics(const nlohmann::json& j) {
  std::map<std::string, double> m;
  for (const auto& r : j.at("held_out").at("records"))
    if (r.at("role") == "held out") m[r.at("record").get<std::string>()] = r.at("metric").get<double>();
  return m;
}

/// Bouc–Wen with c0 linear in I (the coefficients c0_I0, c0_I1, then k0, x0, alpha, beta, gamma, A, n), and a box
/// around them small enough for a short ga-lm run. "A=free" keeps the published parametrization (no state gauge,
/// docs/models.md), so that the truth and its box name A.
const std::vector<double> kBoucWenTruth{1000, 4000, 500, 0, 4e4, 6079, 10830, 120, 0.9929};
constexpr const char* kShared = "k0=0:1000,x0=-0.001:0.001,alpha=2e4:8e4,beta=3000:12000,gamma=5000:20000,A=60:240,n=0.8:1.2";
constexpr const char* kBudget = " --metric nrmse --optimizer ga-lm --pop 16 --iters 10 --runs 2 --seed 3";

TEST(HeldOutCommand, TheTrueLawPredictsHeldOutCurrentsAtTheNoiseFloorAndAWrongOneDoesNot) {
  const Simulated sim("mrd.bouc_wen", "c0=poly(I,1);A=free", kBoucWenTruth, 0);
  const std::string predict = fmt::format(" --predict {} --predict {}", sim.file(0.25), sim.file(0.75));
  const auto right = run_json(fmt::format("fit --model mrd.bouc_wen --laws 'c0=poly(I,1);A=free' --bounds "
                                          "c0_I0=500:2000,c0_I1=2000:8000,{}{}{}{}",
                                          kShared, kBudget, sim.fitted_on(), predict));
  // c0 the same at every current (no law): the joint fit cannot follow the current.
  const auto wrong = run_json(fmt::format("fit --model mrd.bouc_wen --bounds c0=500:6000,{}{}{}{}", kShared, kBudget,
                                          sim.fitted_on(), predict));
  const auto r = held_out_metrics(right), w = held_out_metrics(wrong);
  ASSERT_EQ(r.size(), 2u);
  ASSERT_EQ(w.size(), 2u);
  for (const char* name : {"rec_0.25A", "rec_0.75A"}) {
    EXPECT_LT(r.at(name), 1e-3) << name;
    EXPECT_GT(w.at(name), 1e-2) << name;
    EXPECT_GT(w.at(name), 30 * r.at(name)) << name;
  }
  EXPECT_EQ(right.at("held_out").at("folds").size(), 1u);  // "all": the fit on the --data records
  EXPECT_EQ(right.at("held_out").at("folds")[0].at("name"), "all");
  EXPECT_EQ(right.at("held_out").at("folds")[0].at("best_params"), right.at("best_params"));
  EXPECT_TRUE(right.at("held_out").at("reference").is_null());
  EXPECT_TRUE(right.at("held_out").at("records")[0].at("ratio").is_null());
}

TEST(HeldOutCommand, FoldsGiveTheSameBitsOnOneAndTwoThreads) {
  const Simulated sim("mrd.bouc_wen", "c0=poly(I,1);A=free", kBoucWenTruth, 0);
  const std::string args = fmt::format("fit --model mrd.bouc_wen --laws 'c0=poly(I,1);A=free' --bounds "
                                       "c0_I0=500:2000,c0_I1=2000:8000,{}{}{} --folds leave-one:I --predict {}",
                                       kShared, kBudget, sim.fitted_on(), sim.file(0.25));
  std::string progress;
  auto one = run_json("--threads 1 " + args), two = run_json("--threads 2 " + args, &progress);
  // One progress line per fold fitted, so that a long fold sweep is not silent.
  for (const char* fold : {"I=0", "I=0.5", "I=1"})
    EXPECT_NE(progress.find(fmt::format("fold {}: fitted on 2 records, nrmse ", fold)), std::string::npos) << progress;
  const auto folds = one.at("held_out").at("folds");
  ASSERT_EQ(folds.size(), 4u);  // I=0, I=0.5, I=1, then "all" for --predict
  EXPECT_EQ(folds[0].at("name"), "I=0");
  EXPECT_EQ(folds[0].at("fit"), (std::vector<std::string>{"rec_0.5A", "rec_1A"}));
  EXPECT_EQ(folds[0].at("predict"), (std::vector<std::string>{"rec_0A"}));
  // Two currents determine a line: each fold predicts its left-out current (even by extrapolation).
  for (const auto& [name, metric] : held_out_metrics(one)) EXPECT_LT(metric, 1e-3) << name;
  // The folds' fits are not the fit on all three: each has its own streams and records.
  EXPECT_NE(folds[0].at("fit_value"), one.at("runs").at("best"));
  for (auto* j : {&one, &two}) {
    j->erase("wall_time_s");
    j->erase("candidate_samples_per_s");
  }
  EXPECT_EQ(one.dump(), two.dump());
}

TEST(HeldOutCommand, ReferenceIsTheBaseModelFittedToEachRecordAlone) {
  // Bingham with f_c linear in I, 2 % force noise: the true law predicts 0.25 A about as well as a per-file fit.
  const Simulated sim("mrd.bingham", "f_c=poly(I,1)", {150.0, 300.0, 2500.0, -5.0}, 0.02);
  const auto j = run_json(fmt::format("fit --model mrd.bingham --laws 'f_c=poly(I,1)' --metric nrmse --runs 4 "
                                      "--reference per-file{} --predict {}",
                                      sim.fitted_on(), sim.file(0.25)));
  const auto& h = j.at("held_out");
  EXPECT_EQ(h.at("reference").at("model"), "mrd.bingham");
  const auto& rows = h.at("records");
  ASSERT_EQ(rows.size(), 4u);  // the three fitted records, then the predicted one
  for (int i = 0; i < 4; ++i) {
    const auto& row = rows[i];
    const std::string role = i < 3 ? "fitted" : "held out";
    EXPECT_EQ(row.at("role"), role);
    const double I = i < 3 ? 0.5 * i : 0.25;
    // The per-file value is what `fit` prints for that record alone with its defaults, bit for bit.
    const auto alone = run_json(fmt::format("fit --model mrd.bingham --metric nrmse --data {}", sim.file(I)));
    EXPECT_EQ(bits(row.at("per_file").get<double>()), bits(alone.at("runs").at("best").get<double>())) << I;
    const double metric = row.at("metric").get<double>(), per_file = row.at("per_file").get<double>();
    EXPECT_EQ(bits(row.at("ratio").get<double>()), bits(metric / per_file)) << I;
    // A per-file fit is the best the base model does on its record: the joint fit comes near it, never below.
    EXPECT_GT(metric / per_file, 0.999) << I;
    EXPECT_LT(metric / per_file, 1.2) << I;
  }
  const auto& s = h.at("summary").at("held_out");
  EXPECT_EQ(s.at("count"), 1);
  EXPECT_EQ(s.at("worst_record"), "rec_0.25A");
  EXPECT_EQ(bits(s.at("worst_ratio").get<double>()), bits(rows[3].at("ratio").get<double>()));
  EXPECT_EQ(h.at("summary").at("fitted").at("count"), 3);
}

TEST(HeldOutCommand, ARecordPredictedWithoutAFiniteForceSaysWhyAndTheMeansKeepTheOthers) {
  // f_c = k·I^p + c with k > 0 and p < 0, fitted on 0.5 and 1 A: at 0 A the law gives f_c = inf, so no finite force.
  const Simulated sim("mrd.bingham", "f_c=poly(I,1)", {150.0, 300.0, 2500.0, -5.0}, 0.02);
  const std::string fit = fmt::format("fit --model mrd.bingham --laws 'f_c=power(I)' --bounds f_c_k=10:1000,f_c_p=-1:-0.5 --runs 2 "
                                      "--metric nrmse --reference per-file --data {} --data {} --predict {} --predict {}",
                                      sim.file(0.5), sim.file(1), sim.file(0), sim.file(0.25));
  const auto j = run_json(fit);
  const auto& h = j.at("held_out");
  const auto& rows = h.at("records");
  ASSERT_EQ(rows.size(), 4u);  // the two fitted records, then the two predicted ones
  EXPECT_EQ(rows[2].at("record"), "rec_0A");
  EXPECT_TRUE(rows[2].at("metric").is_null());
  const std::string failure = rows[2].at("failure").get<std::string>();
  EXPECT_NE(failure.find("at I=0"), std::string::npos) << failure;
  EXPECT_NE(failure.find("f_c = inf"), std::string::npos) << failure;
  EXPECT_TRUE(rows[3].at("failure").is_null());
  // Both predicted currents lie below the fitted 0.5–1 A: each is flagged as an extrapolation, the fitted ones not.
  for (int i : {2, 3})
    EXPECT_NE(rows[i].at("extrapolated").get<std::string>().find("(fitted on 0.5 to 1)"), std::string::npos) << i;
  EXPECT_EQ(rows[3].at("extrapolated"), "I = 0.25 (fitted on 0.5 to 1)");
  EXPECT_TRUE(rows[0].at("extrapolated").is_null());
  const auto& s = h.at("summary").at("held_out");
  EXPECT_EQ(s.at("count"), 2);
  EXPECT_EQ(s.at("failed"), 1);
  EXPECT_EQ(bits(s.at("mean").get<double>()), bits(rows[3].at("metric").get<double>()));
  EXPECT_EQ(s.at("worst_record"), "rec_0.25A");
  EXPECT_EQ(h.at("summary").at("fitted").at("failed"), 0);
  const auto md = testing::run_dampbench(fit);
  ASSERT_EQ(md.exit_code, 0) << md.output;
  for (const char* text : {"NO FINITE nrmse (left out of the means): rec_0A (fold all) at I=0", "| no finite nrmse |",
                           "held out rec_0A (fold all): no finite nrmse; at I=0"})
    EXPECT_NE(md.output.find(text), std::string::npos) << text << "\n" << md.output;
}

// fit --start narrowed: three rounds of the mfm paper's bound narrowing over the records, then the laws' box from
// their ranges. Noise-free Bingham records with f_c = 150 + 300·I: the per-record fits are exact, the box's constant
// term is f_c's range at 0 A and its slope bound the range's width over 0-1 A, so the truth sits on the box's corner
// and the fit returns it.
TEST(FitStartNarrowed, TheLawsComeBackFromTheBoxOfTheRecordsNarrowedFits) {
  const Simulated sim("mrd.bingham", "f_c=poly(I,1)", {150.0, 300.0, 2500.0, -5.0}, 0);
  const std::string fit = "fit --model mrd.bingham --laws 'f_c=poly(I,1)' --optimizer ga-lm --pop 20 --iters 10 --runs 2" +
                          sim.fitted_on();
  std::string progress;
  const auto j = run_json(fit + " --start narrowed", &progress);
  EXPECT_NE(progress.find("--start narrowed: bounds narrowed over 3 records in 3 rounds (failed records per round: 0, 0, 0;"),
            std::string::npos)
      << progress;
  const double truth[] = {150.0, 300.0, 2500.0, -5.0};
  const char* names[] = {"f_c_I0", "f_c_I1", "c0", "f0"};
  for (int k = 0; k < 4; ++k)
    EXPECT_NEAR(j.at("best_params").at(names[k]).get<double>(), truth[k], 1e-6 * std::abs(truth[k])) << names[k];
  const auto with_bounds = testing::run_dampbench(fit + " --start narrowed --bounds f0=-10:0");
  EXPECT_NE(with_bounds.exit_code, 0);
  EXPECT_NE(with_bounds.output.find("--start narrowed makes the box from the records' narrowed fits: drop --bounds"),
            std::string::npos)
      << with_bounds.output;
  const auto quadratic = testing::run_dampbench("fit --model mrd.bingham --laws 'f_c=poly(I,2)' --start narrowed" + sim.fitted_on());
  EXPECT_NE(quadratic.exit_code, 0);
  EXPECT_NE(quadratic.output.find("narrow: the law f_c=poly(I,2) has no box from a narrowed range"), std::string::npos)
      << quadratic.output;
}

TEST(HeldOutCommand, BadOptionsAreReportedBeforeTheFit) {
  const Simulated sim("mrd.bingham", "f_c=poly(I,1)", {150.0, 300.0, 2500.0, -5.0}, 0);
  const std::string fit = "fit --model mrd.bingham --laws 'f_c=poly(I,1)' --runs 2" + sim.fitted_on();
  const auto reference = testing::run_dampbench(fit + " --reference pooled");
  EXPECT_NE(reference.exit_code, 0);
  EXPECT_NE(reference.output.find("--reference: expected per-file, got 'pooled'"), std::string::npos) << reference.output;
  const auto folds = testing::run_dampbench(fit + " --folds leave-one:T");
  EXPECT_NE(folds.exit_code, 0);
  EXPECT_NE(folds.output.find("--folds leave-one:T: record 'rec_0A' has no operating variable 'T'"), std::string::npos)
      << folds.output;
  const auto one = testing::run_dampbench(fit + " --folds leave-setting");
  EXPECT_NE(one.exit_code, 0);
  EXPECT_NE(one.output.find("the 3 records give 1 fold (every record has amp=0.01,freq=1)"), std::string::npos) << one.output;
  // Markdown: the folds, the records beside their references, and the means.
  const auto md = testing::run_dampbench(fit + " --folds leave-one:I --reference per-file");
  ASSERT_EQ(md.exit_code, 0) << md.output;
  for (const char* text : {"**Folds (leave-one:I): each fitted on its records, predicting the others**",
                           "| I=0.5 | rec_0A, rec_1A | rec_0.5A |", "| held out | I=1 | rec_1A |",
                           "| fitted | all | rec_0.5A |", "**Means by role**", "| role | records | mean of_abs |"})
    EXPECT_NE(md.output.find(text), std::string::npos) << text << "\n" << md.output;
}

}  // namespace
}  // namespace dampbench
