// Records whose command varies over the test (a current column I(t)): a law model follows the column sample by
// sample in every batch path (engine/model/law_model.hpp, stepped_simulation.hpp), and `fit` identifies the laws and
// the driver's lag τ from such records. Known answers: synthetic Bouc–Wen and Spencer records made by a finely
// stepped truth (32 fixed sub-steps per sample, not the fit's own sub-step rule) under a random-step current (and
// Bouc–Wen under a random current) through a lag of τ = 20 ms, with 1 % Gaussian noise.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "engine/fit/prepared_fit.hpp"
#include "engine/model/law_model.hpp"
#include "engine/model/metrics.hpp"
#include "engine/model/stepped_simulation.hpp"
#include "engine/record/record_options.hpp"
#include "engine/record/record_transforms.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

using testing::bits;

/// A 10 mm, 1.5 Hz sine sampled at 1 kHz for `seconds` under the current `current(t)` [A].
template <class Current>
Dataset sine_record(double seconds, Current current) {
  Dataset d;
  d.name = "command";
  d.source = "test";
  std::vector<double> column;
  const double fs = 1000.0, w = 2 * M_PI * 1.5;
  for (int k = 0; static_cast<double>(k) / fs < seconds; ++k) {
    const double t = static_cast<double>(k) / fs;
    d.t_s.push_back(t);
    d.x_m.push_back(0.01 * std::sin(w * t));
    d.v_m_s.push_back(0.01 * w * std::cos(w * t));
    d.a_m_s2.push_back(-0.01 * w * w * std::sin(w * t));
    column.push_back(current(t));
  }
  d.operating_signals["I"] = column;
  double mean = 0;
  for (double c : column) mean += c / static_cast<double>(column.size());
  d.operating["I"] = mean;
  d.operating_source["I"] = "column mean";
  d.operating_refused["I"] = "varies";
  return d;
}

/// A current that steps between 0, 0.25, 0.5, 0.75 and 1 A every 0.15–0.4 s (levels and durations drawn once at
/// random, written out so that every record holds each level and both directions of steps).
Dataset step_current_record(double seconds) {
  static constexpr std::array<std::pair<double, double>, 12> kSteps{{{0.0, 0.23}, {0.75, 0.31}, {0.25, 0.17},
                                                                     {1.0, 0.28}, {0.5, 0.36}, {0.0, 0.19},
                                                                     {1.0, 0.22}, {0.25, 0.39}, {0.75, 0.16},
                                                                     {0.5, 0.27}, {1.0, 0.33}, {0.0, 0.4}}};
  return sine_record(seconds, [&, step = std::size_t{0}, step_end = kSteps[0].second](double t) mutable {
    while (t >= step_end) step_end += kSteps[++step % kSteps.size()].second;
    return kSteps[step % kSteps.size()].first;
  });
}

/// A random current in 0–1 A: a new uniform level every 50 ms (seeded), linear between them, so that no two
/// samples share a value.
Dataset random_current_record(double seconds) {
  std::mt19937_64 rng(17);
  std::vector<double> levels;
  for (int i = 0; i <= static_cast<int>(seconds / 0.05) + 1; ++i) levels.push_back(static_cast<double>(rng() % 1001) / 1000.0);
  return sine_record(seconds, [&](double t) {
    const auto i = static_cast<std::size_t>(t / 0.05);
    const double th = t / 0.05 - static_cast<double>(i);
    return levels[i] + th * (levels[i + 1] - levels[i]);
  });
}

std::vector<double> named(const Model& m, const std::vector<std::pair<std::string, double>>& values) {
  std::vector<double> p(m.dim(), std::nan(""));
  for (const auto& [name, value] : values) p[m.parameter_index(name)] = value;
  for (std::size_t j = 0; j < p.size(); ++j)
    if (std::isnan(p[j])) ADD_FAILURE() << "no value for " << m.parameters()[j].name;
  return p;
}

/// The record with the truth's force (32 fixed sub-steps per sample) plus 1 % Gaussian noise (of the force's RMS).
Dataset with_truth(Dataset d, const Model& truth, const std::vector<double>& params) {
  std::vector<double> force = simulate_stepped(truth, params, prepare_signals(d), 32);
  double rms = 0;
  for (double f : force) rms += f * f / static_cast<double>(force.size());
  rms = std::sqrt(rms);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 0.01 * rms);
  for (double& f : force) f += noise(rng);
  d.F_N = force;
  return d;
}

struct Recovery {
  std::string base, laws;
  std::vector<std::pair<std::string, double>> truth;
  std::vector<std::string> checked;  ///< the coefficients that must come back within 2 %
  int runs = 2;                      ///< of ga-lm, population 24, 30 iterations
};

std::vector<Recovery> recoveries() {
  return {
      {"mrd.bouc_wen", "c0=poly(I,1);alpha=poly(I,1);tau_I=free;k0=1000;x0=0;n=2",
       {{"c0_I0", 1400}, {"c0_I1", 9600}, {"alpha_I0", 130}, {"alpha_I1", 900}, {"beta", 100}, {"gamma", 300},
        {"tau_I", 0.02}},
       {"c0_I0", "c0_I1", "alpha_I0", "alpha_I1", "tau_I"},
       2},
      {"mrd.spencer", "c0=poly(I,1);alpha=poly(I,1);tau_I=free;c1=2e5;k0=500;k1=100;x0=0;n=2",
       {{"c0_I0", 1400}, {"c0_I1", 9600}, {"alpha_I0", 150}, {"alpha_I1", 1000}, {"beta", 100}, {"gamma", 300},
        {"tau_I", 0.02}},
       {"c0_I0", "c0_I1", "alpha_I0", "alpha_I1", "tau_I"},
       2},
  };
}

/// The box of an engineer who knows the damper (forces of a few kN, a yield displacement 1/(β + γ) of 0.5 mm or
/// more), the truth inside it and off its centre. The default boxes recover the same truths too (`fit` with the
/// automatic budget: 2 min for the Spencer record, Zen 5), but their stiffest candidates, stepped one at a time,
/// cost a hundred times the others.
constexpr const char* kEngineersBox = "c0_I0=0:5000,c0_I1=0:20000,alpha_I0=0:1000,alpha_I1=0:3000,beta=-1000:1000,gamma=0:1000";

FitSpec fit_spec(const Recovery& r, const Dataset& record) {
  FitSpec spec;
  spec.model.model = r.base;
  spec.model.laws = r.laws;
  spec.model.bounds = kEngineersBox;
  spec.records = {record};
  spec.metric = "nrmse";
  spec.optimizer = "ga-lm";
  spec.population = 24;
  spec.iterations = 30;
  spec.runs = r.runs;
  spec.seed = 3;
  return spec;
}

}  // namespace

TEST(VaryingCommand, EveryBatchPathFollowsTheColumnAndAConstantRecordKeepsTheKernels) {
  const Model& base = find_model("mrd.bouc_wen");
  const LawModel law(base, parse_laws("c0=poly(I,1);alpha=poly(I,1);tau_I=free", "test"));
  const auto p = named(law, {{"c0_I0", 1400}, {"c0_I1", 9600}, {"k0", 1000}, {"x0", 0}, {"alpha_I0", 130},
                             {"alpha_I1", 900}, {"beta", 100}, {"gamma", 300}, {"n", 2}, {"tau_I", 0.02}});
  Dataset record = step_current_record(1.0);
  record.F_N.assign(record.size(), 100.0);
  const Signals varying = prepare_signals(record);
  const auto stepped = simulate_stepped(law, p, varying, kKernelSubsteps);
  // simulate, simulate_block, evaluate_block (both precisions) and evaluate_scalar give the stepped force's bits.
  const auto simulated = law.simulate(p, varying);
  ASSERT_EQ(simulated.size(), stepped.size());
  for (std::size_t k = 0; k < stepped.size(); ++k) ASSERT_EQ(bits(simulated[k]), bits(stepped[k])) << "sample " << k;
  // Three candidates, the block from the second: p, then p with another τ (each lane its own candidate).
  auto q = p;
  q[static_cast<std::size_t>(law.parameter_index("tau_I"))] = 0.05;
  const auto stepped_q = simulate_stepped(law, q, varying, kKernelSubsteps);
  CandidateBatch batch(law.dim(), 3);
  for (int j = 0; j < law.dim(); ++j) {
    batch.at(0, j) = 0.5 * p[static_cast<std::size_t>(j)];
    batch.at(1, j) = p[static_cast<std::size_t>(j)];
    batch.at(2, j) = q[static_cast<std::size_t>(j)];
  }
  std::vector<double> block(2 * varying.size());
  law.simulate_block(batch, 1, 2, varying, block.data());
  EXPECT_EQ(bits(block[500]), bits(stepped[500]));
  EXPECT_EQ(bits(block[varying.size() + 500]), bits(stepped_q[500]));
  const MetricSums expected = metric_sums(stepped, varying), expected_q = metric_sums(stepped_q, varying);
  ASSERT_NE(bits(expected.sq), bits(expected_q.sq));
  MetricSums sums[2];
  law.evaluate_block(batch, 1, 2, varying, SumSet::every, sums);
  EXPECT_EQ(bits(sums[0].sq), bits(expected.sq));
  EXPECT_EQ(bits(sums[1].sq), bits(expected_q.sq));
  law.evaluate_block_float32(batch, 1, 2, varying, SumSet::sq, sums);
  EXPECT_EQ(bits(sums[1].sq), bits(expected_q.sq));
  law.evaluate_scalar(batch, 1, 1, varying, SumSet::abs, sums);
  EXPECT_EQ(bits(sums[0].abs), bits(expected.abs));
  // A τ below 0 (a user's box) is a failed candidate, not an error that stops the fit.
  batch.at(2, law.parameter_index("tau_I")) = -0.01;
  law.evaluate_block(batch, 2, 1, varying, SumSet::every, sums);
  EXPECT_TRUE(std::isinf(sums[0].sq));
  // The kernels' sub-step rule is accurate: against 256 fixed sub-steps per sample.
  EXPECT_LT(testing::relative_l2(stepped, simulate_stepped(law, p, varying, 256)), 1e-4);
  // The current matters: the same record at its mean current is another force.
  Dataset constant = record;
  constant.operating_signals.clear();
  constant.operating_refused.clear();
  const Signals held = prepare_signals(constant);
  EXPECT_GT(testing::relative_l2(law.simulate(p, held), stepped), 0.05);
  // A constant record keeps the lane kernels' force (the base at the laws' values).
  const auto kernels = base.simulate(law.base_parameters(p, held), held);
  const auto at_mean = law.simulate(p, held);
  for (std::size_t k = 0; k < kernels.size(); ++k) ASSERT_EQ(bits(at_mean[k]), bits(kernels[k])) << "sample " << k;
}

TEST(VaryingCommand, SubstepsFollowTheStiffestCommandAlsoBehindALag) {
  // γ = 300 + 2e5·I 1/m: at 1 A the gauged Bouc–Wen needs ~38 sub-steps per 1 ms sample, at 0 A the record's few.
  // The current stays within 0.5–1 A: the counts with a lag must be those without it (the lag's u is the command
  // at each probe, never 0 A).
  const Model& base = find_model("mrd.bouc_wen");
  const LawModel plain(base, parse_laws("gamma=poly(I,1)", "test")), lagged(base, parse_laws("gamma=poly(I,1);tau_I=0.02", "test"));
  const std::vector<std::pair<std::string, double>> values{{"c0", 1400}, {"k0", 1000}, {"x0", 0}, {"alpha", 130},
                                                           {"beta", 100}, {"gamma_I0", 300}, {"gamma_I1", 2e5}, {"n", 2}};
  Dataset high = sine_record(1.0, [](double t) { return t < 0.5 ? 0.5 : 1.0; });
  Dataset none = sine_record(1.0, [](double t) { return t < 0.5 ? 0.0 : 0.01; });
  const auto counts = kernel_substeps(plain, named(plain, values), prepare_signals(high));
  EXPECT_EQ(kernel_substeps(lagged, named(lagged, values), prepare_signals(high)), counts);
  const auto at_zero = kernel_substeps(plain, named(plain, values), prepare_signals(none));
  ASSERT_FALSE(counts.empty());
  EXPECT_GT(*std::max_element(counts.begin(), counts.end()), 4 * *std::max_element(at_zero.begin(), at_zero.end()));
}

namespace {

/// Fits r's laws to the truth's force over `motion` (with its current) and expects r.checked within 2 %.
void expect_recovered(const Recovery& r, const Dataset& motion) {
  const LawModel model(find_model(r.base), parse_laws(r.laws, "test"));
  const auto truth = named(model, r.truth);
  const FitOutcome fit = run_fit(prepare_fit(fit_spec(r, with_truth(motion, model, truth))).request());
  const auto& best = fit.best().best_params;
  for (const auto& name : r.checked) {
    const auto j = static_cast<std::size_t>(model.parameter_index(name));
    EXPECT_NEAR(best[j], truth[j], 0.02 * std::fabs(truth[j])) << name;
  }
}

}  // namespace

TEST(VaryingCommand, FitRecoversTheLawsAndTheDriversLagWithinTwoPercent) {
  for (const auto& r : recoveries()) {
    SCOPED_TRACE(r.base);
    expect_recovered(r, step_current_record(2.0));
  }
}

TEST(VaryingCommand, FitRecoversTheLawsAndTheLagUnderARandomCurrent) {
  const Dataset motion = random_current_record(2.0);
  ASSERT_GT(motion.operating_signals.at("I")[101], motion.operating_signals.at("I")[100]);  // no two samples alike
  expect_recovered(recoveries().front(), motion);
}

TEST(VaryingCommand, AFitGivesTheSameBitsOnOneAndTwoThreads) {
  Recovery r = recoveries().front();
  const LawModel model(find_model(r.base), parse_laws(r.laws, "test"));
  const Dataset record = with_truth(step_current_record(0.5), model, named(model, r.truth));
  FitSpec spec = fit_spec(r, record);
  spec.iterations = 5;
  std::vector<std::vector<double>> best;
  for (int threads : {1, 2}) {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, threads);
    const FitOutcome fit = run_fit(prepare_fit(spec).request());
    for (const auto& run : fit.identification.runs) best.push_back(run.best_params);
  }
  ASSERT_EQ(best.size(), 4u);
  for (std::size_t run = 0; run < 2; ++run)
    for (std::size_t j = 0; j < best[run].size(); ++j)
      EXPECT_EQ(bits(best[run][j]), bits(best[run + 2][j])) << "run " << run << ", " << j;
}

TEST(VaryingCommand, CycleAveragingAveragesTheCommandColumn) {
  // Three cycles of the 1.5 Hz sine with the current on for the first 0.3 s of each: one averaged cycle, whose
  // current column has its samples and is still the on/off command (the cycles agree).
  Dataset r = sine_record(2.0, [](double t) { return std::fmod(t, 1.0 / 1.5) < 0.3 ? 1.0 : 0.0; });
  r.F_N.assign(r.size(), 0.0);
  const Dataset one = average_cycles(r, 3, 1);
  const auto& column = one.operating_signals.at("I");
  ASSERT_EQ(column.size(), one.size());
  EXPECT_NEAR(column[100], 1.0, 1e-9);
  EXPECT_NEAR(column[500], 0.0, 1e-9);
}

TEST(VaryingCommand, ALawOfAStatedConstantIgnoresTheColumn) {
  // --set I=... (or a file comment, --conditions) replaces the column: the record is one constant current again.
  Dataset record = step_current_record(0.5);
  record.F_N.assign(record.size(), 1.0);
  Dataset stated = record;
  set_operating(stated, "I=0.5");
  EXPECT_FALSE(stated.operating_signals.count("I"));
  const LawModel law(find_model("mrd.bingham"), parse_laws("f_c=poly(I,1)", "test"));
  EXPECT_FALSE(law.follows_columns(prepare_signals(stated)));
  EXPECT_TRUE(law.follows_columns(prepare_signals(record)));
  // A model without a law in I does not follow it either.
  const LawModel other(find_model("mrd.bingham"), parse_laws("f_c=poly(amp,1)", "test"));
  EXPECT_FALSE(other.follows_columns(prepare_signals(record)));
}

}  // namespace dampbench
