// `fit --laws auto` (engine/fit/law_selection.hpp, engine/fit/value_laws.hpp): on synthetic records generated from
// known laws, the search picks the true families and the joint fit recovers their coefficients. `fit --start
// per-file` (engine/fit/record_start.hpp): laws fitted to the records' own fits start at the true coefficients.
#include "engine/fit/law_selection.hpp"
#include "engine/fit/record_start.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <tuple>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "engine/common/error.hpp"
#include "engine/fit/held_out.hpp"
#include "engine/fit/prepared_fit.hpp"
#include "engine/model/law_model.hpp"
#include "engine/record/excitation.hpp"
#include "models/registry.hpp"
#include "optimizers/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

TEST(ValueLaws, FitsAHillLawTimesALinearFactorItWasGeneratedFrom) {
  // y = (20 + 300·I²/(0.5² + I²))·(1 + 0.4·freq) at five currents and three frequencies
  const ValueLaw law{ValueLaw::Shape::hill2, ValueLaw::Factor::linear, "freq"};
  EXPECT_EQ(law.text(), "prod(hill(I,2),poly(freq,1))");
  EXPECT_EQ(law.coefficients(), 5);
  std::vector<std::map<std::string, double>> vars;
  std::vector<double> y;
  for (double f : {0.5, 1.0, 3.0})
    for (double I : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      vars.push_back({{"I", I}, {"freq", f}});
      y.push_back((20 + 300 * I * I / (0.25 + I * I)) * (1 + 0.4 * f));
    }
  const ValueFit fit = fit_value_law(law, vars, y);
  // h from a grid over 0.05–2 A refined by golden-section search, the factor by alternating least squares
  EXPECT_NEAR(fit.coefficients[2], 0.5, 0.05);
  EXPECT_NEAR(fit.coefficients[4] / fit.coefficients[3], 0.4, 0.02);
  for (std::size_t i = 0; i < y.size(); ++i) EXPECT_NEAR(fit.predict(law, vars[i]), y[i], 0.02 * y[i] + 1);
  // a linear law in I cannot follow the sigmoid: its residuals are far larger
  EXPECT_GT(fit_value_law({ValueLaw::Shape::linear, ValueLaw::Factor::linear, "freq"}, vars, y).rss, 100 * fit.rss);
}

TEST(ValueLaws, FitsAViscousCoefficientFallingAsOneOverTheVelocityAmplitude) {
  // c0 = (500 + 2000·I)·0.05/vamp: a post-yield force that does not grow with velocity
  const ValueLaw law{ValueLaw::Shape::linear, ValueLaw::Factor::power, "vamp"};
  EXPECT_EQ(law.text(), "prod(mono(I,0,1),power(vamp))");
  EXPECT_EQ(law.coefficients(), 5);
  std::vector<std::map<std::string, double>> vars;
  std::vector<double> y;
  for (double vamp : {0.0157, 0.0393, 0.0628, 0.0942})
    for (double I : {0.0, 0.5, 1.0}) {
      vars.push_back({{"I", I}, {"vamp", vamp}});
      y.push_back((500 + 2000 * I) * 0.05 / vamp);
    }
  const ValueFit fit = fit_value_law(law, vars, y);
  ASSERT_EQ(fit.coefficients.size(), 5u);
  // a, b, then power's k, p, c: the factor is 1 at the geometric-mean vamp, so F(I) is c0 there
  const double mean_vamp = std::pow(0.0157 * 0.0393 * 0.0628 * 0.0942, 0.25);
  EXPECT_NEAR(fit.coefficients[2], mean_vamp, 0.01 * mean_vamp);
  EXPECT_NEAR(fit.coefficients[3], -1.0, 0.02);
  EXPECT_NEAR(fit.coefficients[4], 0.0, 0.01);
  EXPECT_NEAR(fit.coefficients[0], 500 * 0.05 / mean_vamp, 0.01 * 500 * 0.05 / mean_vamp);
  for (std::size_t i = 0; i < y.size(); ++i) EXPECT_NEAR(fit.predict(law, vars[i]), y[i], 0.01 * y[i]);
  // a linear factor in the same variable misses the 1/vamp curve by far more
  EXPECT_GT(fit_value_law({ValueLaw::Shape::linear, ValueLaw::Factor::linear, "freq"}, vars, y).rss, 100 * fit.rss + 1);
}

TEST(ValueLaws, FitsAHystereticRateFallingAsAPowerOfTheStroke) {
  // beta = -300·amp^-0.8 + 50 [1/m], shared by the currents: a yield displacement that grows with the stroke
  const ValueLaw law{ValueLaw::Shape::constant, ValueLaw::Factor::power, "amp"};
  EXPECT_EQ(law.text(), "power(amp)");
  EXPECT_EQ(law.coefficients(), 3);
  std::vector<std::map<std::string, double>> vars;
  std::vector<double> y;
  for (double amp : {0.002, 0.005, 0.01, 0.025})
    for (double I : {0.0, 0.5, 1.0}) {
      vars.push_back({{"I", I}, {"amp", amp}});
      y.push_back(-300 * std::pow(amp, -0.8) + 50);
    }
  const ValueFit fit = fit_value_law(law, vars, y);
  ASSERT_EQ(fit.coefficients.size(), 3u);
  EXPECT_NEAR(fit.coefficients[0], -300, 3);
  EXPECT_NEAR(fit.coefficients[1], -0.8, 0.008);
  EXPECT_NEAR(fit.coefficients[2], 50, 0.01 * 300 * std::pow(0.025, -0.8));
  // a linear law in amp misses the curve by far more
  EXPECT_GT(fit_value_law({ValueLaw::Shape::constant, ValueLaw::Factor::linear, "amp"}, vars, y).rss, 100 * fit.rss + 1);
}

TEST(ValueLaws, EachFamilysCoefficientsMeanTheSameInTheLawGrammar) {
  // a law model evaluates the law text with the fitted coefficients: both must give the same parameter values
  std::vector<std::map<std::string, double>> vars;
  std::vector<double> y;
  for (auto [amp, freq] : {std::pair{0.025, 0.1}, {0.01, 1.0}, {0.002, 5.0}})
    for (double I : {0.0, 0.5, 1.0}) {
      vars.push_back({{"I", I}, {"amp", amp}, {"freq", freq}, {"vamp", 2 * std::numbers::pi * amp * freq}});
      y.push_back((100 + 900 * I / (0.3 + I)) * (1 + 0.2 * freq + 0.01 / vars.back().at("vamp")));
    }
  for (const ValueLaw& law : value_law_candidates()) {
    const ValueFit fit = fit_value_law(law, vars, y);
    const ParameterLaw parsed = parse_law(law.text(), "test");
    ASSERT_EQ(static_cast<int>(fit.coefficients.size()), law.coefficients()) << law.text();
    ASSERT_EQ(static_cast<int>(parsed.coefficient_names("p").size()), law.coefficients()) << law.text();
    for (const auto& v : vars) {
      const double expected = fit.predict(law, v);
      EXPECT_NEAR(parsed.evaluate(fit.coefficients.data(), v), expected, 1e-9 * std::fabs(expected)) << law.text();
    }
  }
}

TEST(ValueLaws, ADecreasingTrendFallsBackToAConstantBecauseLawsRiseWithCurrent) {
  const std::vector<std::map<std::string, double>> vars{{{"I", 0.0}}, {{"I", 0.5}}, {{"I", 1.0}}};
  const ValueFit fit = fit_value_law({ValueLaw::Shape::linear, ValueLaw::Factor::none, ""}, vars, {3.0, 2.0, 1.0});
  EXPECT_EQ(fit.coefficients[1], 0.0);
  EXPECT_DOUBLE_EQ(fit.coefficients[0], 2.0);
  EXPECT_EQ(ValueLaw{}.text(), "free");
  EXPECT_EQ((ValueLaw{ValueLaw::Shape::constant, ValueLaw::Factor::linear, "amp"}.text()), "poly(amp,1)");
  EXPECT_EQ(value_law_candidates().size(), 24u);
}

/// The true Bingham parameters (f_c, c0, f0) at a current: f_c = hill(I,2) (60, 500, 0.6 A), c0 linear in I
/// (1000 + 2000·I) and f0 = 5 N shared.
std::vector<double> bingham_truth(double current) {
  return {60 + 500 * current * current / (0.36 + current * current), 1000 + 2000 * current, 5.0};
}

/// A Bingham record (F = f_c·sgn(v) + c0·v + f0) on a sine with the true parameters at `current`.
Signals bingham_record(double amp, double freq, double current) {
  SineSpec spec;
  spec.amplitude_m = amp, spec.freq_hz = freq, spec.cycles = 2, spec.fs_hz = 400 * freq;
  Dataset d = make_sine(spec);
  d.operating["I"] = current;
  const std::vector<double> p = bingham_truth(current);
  d.F_N = find_model("mrd.bingham").simulate(p, prepare_signals(d));
  d.name = fmt::format("{}mm{}Hz{}A", amp * 1e3, freq, current);
  return prepare_signals(d);
}

/// The search of a Bingham law model on `records` with ga-lm 24 × 30, two runs, nrmse.
LawSearch bingham_search(const std::vector<Signals>& records) {
  static const OptimizerFactory factory = make_optimizer_factory({"ga-lm", 24, 30});
  LawSearch search;
  search.base = &find_model("mrd.bingham");
  for (const auto& r : records) search.records.push_back(&r);
  search.optimizer = &factory;
  search.optimizer_name = "ga-lm";
  search.settings.runs = 2;
  search.settings.metric = Metric::nrmse;
  return search;
}

TEST(LawSelection, PicksTheTrueFamiliesAndRecoversTheirCoefficients) {
  std::vector<Signals> records;
  for (auto [amp, freq] : {std::pair{0.01, 1.0}, {0.005, 2.0}, {0.02, 0.5}})
    for (double I : {0.0, 0.25, 0.5, 0.75, 1.0}) records.push_back(bingham_record(amp, freq, I));
  const LawSearch search = bingham_search(records);
  ResolvedModel fitted;
  LawSelection selection;
  const FitOutcome outcome = fit_with_auto_laws(search, fitted, selection);
  EXPECT_EQ(selection.laws, "f_c=hill(I,2);c0=mono(I,0,1)");
  EXPECT_LT(selection.score, 0.1 * selection.shared_score);
  const auto& c = outcome.best().best_params;
  ASSERT_EQ(c.size(), 6u);  // f_c: a, b, h; c0: two; f0
  const double truth[] = {60, 500, 0.6, 1000, 2000, 5};
  for (std::size_t j = 0; j < c.size(); ++j) EXPECT_NEAR(c[j], truth[j], 0.02 * truth[j]) << j;

  // same bits on one thread
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  ResolvedModel fitted1;
  LawSelection selection1;
  const FitOutcome outcome1 = fit_with_auto_laws(search, fitted1, selection1);
  EXPECT_EQ(selection1.laws, selection.laws);
  EXPECT_EQ(outcome1.best().best_params, c);
}

/// The choice on the records' true parameters (no per-record fits): its fold table and score.
LawSelection select_on_true_parameters(const std::vector<double>& currents) {
  std::vector<Signals> records;
  for (auto [amp, freq] : {std::pair{0.01, 1.0}, {0.02, 0.5}})
    for (double I : currents) records.push_back(bingham_record(amp, freq, I));
  std::vector<std::vector<double>> truth;
  for (const auto& r : records) truth.push_back(bingham_truth(r.law_variables.at("I")));
  const LawSearch search = bingham_search(records);
  return select_laws(search, gauged_model(*search.base), truth);
}

/// The fold table's left-out mean of the chosen laws over the rows [begin, end), weighted by their records.
double mean_of_rows(const Table& folds, std::size_t begin, std::size_t end) {
  double sum = 0, n = 0;
  for (std::size_t i = begin; i < end; ++i) {
    const double records = std::stod(folds.rows[i][1].text);
    sum += records * folds.rows[i][3].value.value(), n += records;
  }
  return sum / n;
}

TEST(LawSelection, LeavesTheInnerCurrentsOutWhenTheRecordsHoldFourOrMore) {
  // Four currents: two settings, then 0.25 and 0.5 A (not 0 or 1 A, which would be extrapolated); the score is the
  // mean of the two kinds' means.
  const LawSelection four = select_on_true_parameters({0.0, 0.25, 0.5, 1.0});
  ASSERT_EQ(four.folds.rows.size(), 4u);
  EXPECT_EQ(four.folds.rows[0][1].text, "4");
  EXPECT_EQ(four.folds.rows[2][0].text, "I 0.25 A");
  EXPECT_EQ(four.folds.rows[3][0].text, "I 0.5 A");
  EXPECT_EQ(four.folds.rows[3][1].text, "2");
  const double expected = 0.5 * (mean_of_rows(four.folds, 0, 2) + mean_of_rows(four.folds, 2, 4));
  EXPECT_NEAR(four.score, expected, 1e-12 * expected);
  EXPECT_EQ(four.laws, "f_c=hill(I,2);c0=mono(I,0,1)");

  // Three currents leave two when one is out, which cannot judge a three-coefficient shape: settings only.
  const LawSelection three = select_on_true_parameters({0.0, 0.5, 1.0});
  ASSERT_EQ(three.folds.rows.size(), 2u);
  EXPECT_NE(three.folds.note.find("with 3 training currents"), std::string::npos) << three.folds.note;
  EXPECT_EQ(four.folds.note, "");
  EXPECT_NEAR(three.score, mean_of_rows(three.folds, 0, 2), 1e-12 * three.score);
}

TEST(LawSelection, ClampsAPredictionIntoTheTrainingRecordsBoxesNotTheLeftOutRecordsOwn) {
  // Bouc-Wen under its gauge (alpha the hysteretic force in N, its box 0 to 2 F of the record), two settings that
  // differ only in alpha: 100 N at 10 mm-1 Hz (peak force about 130 N, so its own box stops alpha at about 260 N)
  // and 1000 N at 20 mm-0.5 Hz. Leaving the first out, every parameter shared predicts alpha = 1000 N, inside the
  // training record's box: the left-out record is simulated with it, not with alpha cut down to its own force.
  const ResolvedModel gauged = gauged_model(find_model("mrd.bouc_wen"));
  const Model& model = *gauged.model;
  const auto with_alpha = [&](double alpha) {
    const std::map<std::string, double> value{{"c0", 500},    {"k0", 200},    {"x0", 0}, {"alpha", alpha},
                                              {"beta", 100}, {"gamma", 200}, {"n", 1.5}};
    std::vector<double> p;
    for (const auto& info : model.parameters()) p.push_back(value.at(info.name));
    return p;
  };
  std::vector<Signals> records;
  std::vector<std::vector<double>> truth;
  for (auto [amp, freq, alpha] : {std::tuple{0.01, 1.0, 100.0}, {0.02, 0.5, 1000.0}})
    for (double I : {0.0, 1.0}) {
      SineSpec spec;
      spec.amplitude_m = amp, spec.freq_hz = freq, spec.cycles = 2, spec.fs_hz = 400 * freq;
      Dataset d = make_sine(spec);
      d.operating["I"] = I;
      truth.push_back(with_alpha(alpha));
      d.F_N = model.simulate(truth.back(), prepare_signals(d));
      d.name = fmt::format("{}mm{}A", amp * 1e3, I);
      records.push_back(prepare_signals(d));
    }
  ASSERT_GT(1000.0, 2 * records[0].measured_max_abs);  // the left-out record's own box would cut alpha
  LawSearch search = bingham_search(records);
  search.base = &find_model("mrd.bouc_wen");
  const LawSelection selection = select_laws(search, gauged, truth);
  double expected = 0;
  for (std::size_t r = 0; r < records.size(); ++r)
    expected += record_metric(model, truth[(r + 2) % 4], records[r], Metric::nrmse) / 4;
  EXPECT_NEAR(selection.shared_score, expected, 1e-12 * expected);
}

TEST(RecordStart, FitsEachLawToValuesItWasGeneratedFrom) {
  const std::vector<std::map<std::string, double>> vars{{{"I", 0.0}}, {{"I", 0.5}}, {{"I", 1.0}}};
  // 2 + 3·I + 4·I² at 0, 0.5, 1 A: 2, 4.5, 9; three currents determine a quadratic
  const auto quadratic = fit_law_to_values(parse_law("poly(I,2)", "test"), "c1", vars, {2.0, 4.5, 9.0});
  ASSERT_EQ(quadratic.size(), 3u);
  EXPECT_NEAR(quadratic[0], 2.0, 1e-12);
  EXPECT_NEAR(quadratic[1], 3.0, 1e-12);
  EXPECT_NEAR(quadratic[2], 4.0, 1e-12);
  EXPECT_EQ(fit_law_to_values(parse_law("free", "test"), "n", vars, {1.0, 2.0, 6.0}), std::vector<double>{3.0});
  EXPECT_TRUE(fit_law_to_values(parse_law("2", "test"), "n", vars, {1.0, 2.0, 6.0}).empty());
  // sat(I) through 10 + 20·(1 − e^(−I/0.3)), by value_laws.hpp's fit
  std::vector<double> y;
  for (const auto& v : vars) y.push_back(10 + 20 * (1 - std::exp(-v.at("I") / 0.3)));
  const auto sat = fit_law_to_values(parse_law("sat(I)", "test"), "alpha", vars, y);
  ASSERT_EQ(sat.size(), 3u);
  EXPECT_NEAR(sat[0], 10, 1e-3);
  EXPECT_NEAR(sat[1], 20, 1e-2);
  EXPECT_NEAR(sat[2], 0.3, 1e-3);
  try {
    fit_law_to_values(parse_law("tanh(I)", "test"), "c0", vars, y);
    FAIL() << "tanh(I) has no value fit";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("c0=tanh(I)"), std::string::npos) << e.what();
  }
}

TEST(RecordStart, LawsFittedToEachRecordsOwnFitStartAtTheTrueCoefficients) {
  std::vector<Signals> records;
  for (double I : {0.0, 0.25, 0.5, 0.75, 1.0}) records.push_back(bingham_record(0.01, 1.0, I));
  const LawSearch search = bingham_search(records);
  ModelChoice choice;
  choice.model = "mrd.bingham";
  choice.laws = "f_c=hill(I,2);c0=poly(I,1)";
  choice.option_prefix = "--";
  const ResolvedModel law_model = resolve_model(choice);
  EXPECT_EQ(per_record_model(choice).model->dim(), 3);
  const auto start = start_from_record_fits(search, choice, *law_model.model);
  ASSERT_EQ(start.size(), 6u);
  const double truth[] = {60, 500, 0.6, 1000, 2000, 5};
  for (std::size_t j = 0; j < start.size(); ++j) EXPECT_NEAR(start[j], truth[j], 0.02 * truth[j]) << j;
}

TEST(RecordStart, RefusesAnUnknownStartAndOneBesideLawsAuto) {
  FitSpec spec;
  spec.model.model = "mrd.bingham";
  spec.start = "median";
  EXPECT_THROW(prepare_fit(spec), InputError);
  spec.start = "per-file";
  spec.model.laws = "auto";
  EXPECT_THROW(prepare_fit(spec), InputError);
}

}  // namespace
}  // namespace dampbench
