// Stiff-safe ODE lanes (engine/kernels/ode_kernel.hpp, "Stiff lanes"): over random candidates
// drawn uniformly from each MR ODE model's default box on a UTFSM-like record (10 mm, 1 Hz, 1 kHz), fewer
// than 5 % are masked, and every candidate that is not masked matches SUNDIALS CVODE (BDF, rtol 1e-10) to a
// relative L2 difference below 1e-4, in double lanes and in the single-precision lanes of `--precision mixed`;
// the same bound on the gauged box of a joint fit of two strokes.
// A lane's result does not depend on its block-mates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "engine/common/random.hpp"
#include "engine/evaluation/batch_evaluator.hpp"
#include "engine/model/bounds.hpp"
#include "engine/model/law_model.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

/// `count` candidates drawn uniformly from the box, candidate i from the stream (key, i).
CandidateBatch random_candidates(const Bounds& box, int count, std::uint64_t key) {
  CandidateBatch batch(box.dim(), count);
  for (int i = 0; i < count; ++i) {
    RandomStream rng(hash_key({key, static_cast<std::uint64_t>(i)}));
    for (int j = 0; j < box.dim(); ++j) batch.at(i, j) = rng.uniform(box.lower[j], box.upper[j]);
  }
  return batch;
}

std::vector<double> row(const CandidateBatch& batch, int i) {
  std::vector<double> p(batch.dim());
  for (int j = 0; j < batch.dim(); ++j) p[j] = batch.at(i, j);
  return p;
}

/// A UTFSM-like record: 10 mm, 1 Hz, two cycles at 1 kHz, 1 V for the voltage models, and a viscous force
/// of 1 kN peak (the metrics only need some force to normalize by).
Signals utfsm_like_record() {
  Signals data = testing::sine_signals(0.01, 1.0, 2, 1000, {{"V", 1.0}});
  data.F_N.resize(data.size());
  for (std::size_t k = 0; k < data.size(); ++k) data.F_N[k] = 1000.0 * data.v_m_s[k] / data.velocity_max_abs;
  return prepare_signals(data);
}

struct BoxReport {
  double masked_share = 0;
  double worst_rel_l2 = 0;
  int worst_candidate = -1;
};

/// With `float32`, the single-precision lanes (evaluate_block_float32, simulate_float32) against CVODE in double.
BoxReport check_box(const std::string& id, int count, bool float32 = false) {
  const Model& model = find_model(id);
  const Signals data = utfsm_like_record();
  const Signals* records[] = {&data};
  const Bounds box = default_bounds(model, records);
  const CandidateBatch batch = random_candidates(box, count, hash_name(id));
  std::vector<double> values(count);
  BatchEvaluator(model, data, 1, float32 ? Precision::float32 : Precision::float64).evaluate(batch, Metric::nrmse, values);
  BoxReport r;
  int masked = 0;
  for (int i = 0; i < count; ++i) {
    if (!std::isfinite(values[i])) {
      ++masked;
      if (std::getenv("DAMPBENCH_DEBUG_STIFF")) {
        for (double v : row(batch, i)) std::printf("%g ", v);
        std::printf("\n");
      }
      continue;
    }
    const auto p = row(batch, i);
    const auto force = float32 ? model.simulate_float32(p, data) : model.simulate(p, data);
    const double d = testing::relative_l2(force, *model.simulate_reference(p, data));
    if (!(d <= r.worst_rel_l2)) r.worst_rel_l2 = d, r.worst_candidate = i;
    if (std::getenv("DAMPBENCH_DEBUG_STIFF") && !(d < 1e-4)) {
      std::printf("candidate %d, relative L2 %g:", i, d);
      for (double v : p) std::printf(" %g", v);
      std::printf("\n");
    }
  }
  r.masked_share = static_cast<double>(masked) / count;
  std::printf("%s (%s lanes): %d random candidates of the default box, %.1f %% masked, worst relative L2 to CVODE %.3g (candidate %d)\n",
              id.c_str(), float32 ? "float32" : "float64", count, 100 * r.masked_share, r.worst_rel_l2, r.worst_candidate);
  return r;
}

}  // namespace

class StiffLanes : public ::testing::TestWithParam<std::string> {};

TEST_P(StiffLanes, DefaultBoxIsIntegratedNotMaskedAndMatchesCvode) {
  const BoxReport r = check_box(GetParam(), 100);
  EXPECT_LT(r.masked_share, 0.05);
  EXPECT_LT(r.worst_rel_l2, 1e-4) << "candidate " << r.worst_candidate;
}

// The global search of `--precision mixed` runs these models in float lanes: the CVODE bound holds there too,
// and the float lanes are float (their forces differ from the double lanes' by float rounding, not by nothing).
TEST_P(StiffLanes, Float32LanesMatchCvodeOnTheDefaultBox) {
  const Model& model = find_model(GetParam());
  if (!model.has_float32_lanes()) GTEST_SKIP() << GetParam() << " has no float32 lanes";
  const BoxReport r = check_box(GetParam(), 100, true);
  EXPECT_LT(r.masked_share, 0.05);
  EXPECT_LT(r.worst_rel_l2, 1e-4) << "candidate " << r.worst_candidate;
  const Signals data = utfsm_like_record();
  const Signals* records[] = {&data};
  const Bounds box = default_bounds(model, records);
  const auto p = row(random_candidates(box, 1, hash_name(GetParam())), 0);
  const double d = testing::relative_l2(model.simulate_float32(p, data), model.simulate(p, data));
  std::printf("float32 against float64 lanes: relative L2 %.3g\n", d);
  EXPECT_GT(d, 1e-9);
  EXPECT_LT(d, 1e-5);
}

// A law model's joint fit of records of different strokes searches the gauged box (A = β + γ) that holds in each
// record's own (RecordBoundsRule::stiffening): on both records, its candidates that are not masked match CVODE.
// The gauged box is stiffer than the ungauged default (z saturates over as little as X/4000): a quarter of its
// candidates take more than the kernel's most sub-steps per sample and are masked, which the test reports.
TEST_P(StiffLanes, GaugedBoxOfTwoStrokesMatchesCvodeOnBoth) {
  const Model& base = find_model(GetParam());
  if (!base.state_gauge()) GTEST_SKIP() << GetParam() << " has no state gauge";
  const LawModel gauged(base, {});
  Signals short_stroke = testing::sine_signals(0.002, 5.0, 2, 200, {{"V", 1.0}});  // 2 mm, 5 Hz at 200 Hz (UTFSM)
  short_stroke.F_N.resize(short_stroke.size());
  for (std::size_t k = 0; k < short_stroke.size(); ++k)
    short_stroke.F_N[k] = 1000.0 * short_stroke.v_m_s[k] / short_stroke.velocity_max_abs;
  const Signals records[] = {utfsm_like_record(), prepare_signals(short_stroke)};
  const Signals* both[] = {&records[0], &records[1]};
  const Bounds box = default_bounds(gauged, both);
  const int count = 100;
  const CandidateBatch batch = random_candidates(box, count, hash_key({hash_name(GetParam()), 2}));
  for (const Signals& data : records) {
    std::vector<double> values(count);
    BatchEvaluator(gauged, data).evaluate(batch, Metric::nrmse, values);
    int masked = 0, worst = -1;
    double worst_l2 = 0;
    for (int i = 0; i < count; ++i) {
      if (!std::isfinite(values[i])) {
        ++masked;
        continue;
      }
      const auto p = row(batch, i);
      const double d = testing::relative_l2(gauged.simulate(p, data), *gauged.simulate_reference(p, data));
      if (!(d <= worst_l2)) worst_l2 = d, worst = i;
    }
    std::printf("%s gauged, box of both strokes, on the %.0f mm record: %d of %d masked, worst relative L2 to CVODE "
                "%.3g (candidate %d)\n",
                GetParam().c_str(), 1e3 * 0.5 * data.displacement_ptp, masked, count, worst_l2, worst);
    EXPECT_LT(worst_l2, 1e-4) << "candidate " << worst;
    EXPECT_LT(masked, count / 2) << "most of the box masked: the bound would hold on too few candidates";
  }
}

// A lane's sub-steps come from its own parameters: a mild Spencer candidate gives the same bits alone and in
// a lane block with a stiff one (which makes the block take the per-lane path).
TEST(StiffLanes, LaneResultDoesNotDependOnItsBlockMates) {
  const Model& model = find_model("mrd.spencer");
  const Signals data = utfsm_like_record();
  // z_max = 1 cm, transition over 0.5 mm (the record's sub-steps suffice) against z_max = 5.5 mm reached
  // within 18 µm (about 14 sub-steps per 1 ms sample: 7 × the record's).
  const std::vector<double> mild = {4110.0, 4.542e5, 42.83, 561.2, 0.0, 1.5e4, 1e5, 1e5, 20.0, 2.0};
  std::vector<double> stiff = mild;
  stiff[model.parameter_index("A")] = 300.0;
  stiff[model.parameter_index("beta")] = 5e6;
  stiff[model.parameter_index("gamma")] = 5e6;
  CandidateBatch alone(model.dim(), 1), mixed(model.dim(), 2);
  for (int j = 0; j < model.dim(); ++j) {
    alone.at(0, j) = mild[j];
    mixed.at(0, j) = stiff[j];
    mixed.at(1, j) = mild[j];
  }
  std::vector<double> a(1), m(2);
  BatchEvaluator(model, data).evaluate(alone, Metric::nrmse, a);
  BatchEvaluator(model, data).evaluate(mixed, Metric::nrmse, m);
  ASSERT_TRUE(std::isfinite(m[0])) << "the stiff candidate must be integrated, not masked";
  EXPECT_EQ(a[0], m[1]);
  // and the stiff one is right: CVODE agrees
  EXPECT_LT(testing::relative_l2(model.simulate(stiff, data), *model.simulate_reference(stiff, data)), 1e-4);
}

INSTANTIATE_TEST_SUITE_P(MrOdeModels, StiffLanes,
                         ::testing::Values("mrd.bouc_wen", "mrd.spencer", "mrd.spencer_voltage"),
                         [](const auto& param_info) {
                           std::string name = param_info.param.substr(4);
                           std::replace(name.begin(), name.end(), '.', '_');
                           return name;
                         });

}  // namespace dampbench
