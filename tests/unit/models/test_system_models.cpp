// System models (models/structure.cpp): sys.bouc_wen against its CVODE reference, its response to a periodic input
// in steady state, and a system record's metrics in metres.
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "engine/kernels/isa.hpp"
#include "engine/model/model.hpp"
#include "engine/record/signals.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

constexpr double kPi = std::numbers::pi;
const std::vector<double> kTable1{2, 10, 5e4, 5e4, 800, -1100, 1};

/// A t, u record at 750 Hz: a 40 N sine sweep from 20 Hz at 10 Hz/min over `seconds`, the structure at rest before.
Dataset sweep_input(double seconds) {
  Dataset d;
  d.name = "sweep";
  for (int k = 0; k <= static_cast<int>(seconds * 750); ++k) {
    const double t = k / 750.0;
    d.t_s.push_back(t);
    d.u_N.push_back(40 * std::sin(2 * kPi * (20 * t + t * t / 12)));
  }
  return d;
}

TEST(SystemModels, BoucWenNewmarkAgreesWithCvode) {
  // Newmark's average-acceleration rule at 15 kHz has a period error of (ωh)²/12 = 2e-5 at the 35.6 Hz resonance;
  // CVODE (BDF, rtol 1e-10) on the same reconstructed input measures what that costs in y.
  const Model& model = find_model("sys.bouc_wen");
  const Signals data = prepare_signals(sweep_input(4));
  const std::vector<double> lanes = model.simulate(kTable1, data);
  const std::vector<double> reference = *model.simulate_reference(kTable1, data);
  const double error = testing::relative_l2(lanes, reference);
  RecordProperty("relative_l2", fmt::format("{:.3g}", error));
  EXPECT_LT(error, 1e-4);  // the CVODE bound of the ODE models (docs/models.md)
}

TEST(SystemModels, PeriodicInputScoresTheSteadyPeriod) {
  // One period of a periodic input: the model's answer equals the last of several periods simulated from rest.
  const Model& model = find_model("sys.bouc_wen");
  Dataset period;
  for (int k = 0; k < 750; ++k) {  // 1 s: 30 N at 12 Hz and 20 N at 41 Hz
    const double t = k / 750.0;
    period.t_s.push_back(t);
    period.u_N.push_back(30 * std::sin(2 * kPi * 12 * t) + 20 * std::cos(2 * kPi * 41 * t));
  }
  period.periodic_input = true;
  const std::vector<double> steady = model.simulate(kTable1, prepare_signals(period));
  Dataset repeated;
  for (int p = 0; p < 4; ++p)
    for (int k = 0; k < 750; ++k) {
      repeated.t_s.push_back(p + k / 750.0);
      repeated.u_N.push_back(period.u_N[k]);
    }
  repeated.periodic_input = true;  // the FFT reconstruction of four periods is that of one, repeated
  const std::vector<double> four = model.simulate(kTable1, prepare_signals(repeated));
  const std::vector<double> last(four.end() - 750, four.end());
  EXPECT_LT(testing::relative_l2(steady, last), 1e-9);
  repeated.periodic_input = false;  // from rest, the first period still carries the free response
  const std::vector<double> from_rest = model.simulate(kTable1, prepare_signals(repeated));
  EXPECT_GT(testing::relative_l2(std::vector<double>(from_rest.begin(), from_rest.begin() + 750), steady), 1e-3);
}

TEST(SystemModels, MetricsOfASystemRecordAreInMetres) {
  const Model& model = find_model("sys.bouc_wen");
  Dataset d = sweep_input(1);
  Signals input = prepare_signals(d);
  d.y_m = model.simulate(kTable1, input);
  for (double& y : d.y_m) y += 1e-6;  // a known offset: rmse = mae = 1e-6 m
  const Signals data = prepare_signals(d);
  CandidateBatch batch(model.dim(), 1);
  batch.set_candidate(0, kTable1);
  MetricSums sums;
  model.evaluate_block(batch, 0, 1, data, SumSet::every, &sums);
  EXPECT_NEAR(finish_metric(Metric::rmse, sums, data), 1e-6, 1e-15);
  EXPECT_NEAR(finish_metric(Metric::mae, sums, data), 1e-6, 1e-15);
}

TEST(SystemModels, SameBitsInBlocksOfEitherWidth) {
  // Five candidates run in a narrow block (≤ 8 lanes), then as the first five of twelve in a kLanes block: the same
  // displacements and metric sums bit for bit, at every vector level this CPU has. Table 1 and four others around it
  // (ν ≠ 1 takes the vector exp and log of |z|^ν; the others differ in every parameter).
  const Model& model = find_model("sys.bouc_wen");
  Dataset measured = sweep_input(0.5);
  measured.y_m = model.simulate(kTable1, prepare_signals(measured));
  const Signals data = prepare_signals(measured);
  const std::vector<std::vector<double>> five{kTable1,
                                              {1.5, 20, 8e4, 3e4, 1200, -700, 0.6},
                                              {3, 5, 4e4, 9e4, 500, -2000, 1.7},
                                              {2.2, 12, 5.5e4, 4.5e4, 900, -1000, 2.5},
                                              {0.8, 40, 1.2e5, 1.5e4, 300, -400, 0.3}};
  CandidateBatch twelve(model.dim(), 12);
  for (int i = 0; i < 12; ++i) twelve.set_candidate(i, five[i % 5]);
  const Isa saved = active_isa();
  for (const Isa isa : supported_isas()) {
    select_isa(isa);
    const std::size_t n = data.size();
    std::vector<double> narrow(5 * n), wide(12 * n);
    model.simulate_block(twelve, 0, 5, data, narrow.data());
    model.simulate_block(twelve, 0, 12, data, wide.data());
    EXPECT_EQ(std::memcmp(narrow.data(), wide.data(), 5 * n * sizeof(double)), 0) << isa_name(isa);
    std::vector<MetricSums> narrow_sums(5), wide_sums(12);
    model.evaluate_block(twelve, 0, 5, data, SumSet::every, narrow_sums.data());
    model.evaluate_block(twelve, 0, 12, data, SumSet::every, wide_sums.data());
    for (int i = 0; i < 5; ++i)
      EXPECT_EQ(std::memcmp(&narrow_sums[i], &wide_sums[i], sizeof(MetricSums)), 0) << isa_name(isa) << " candidate " << i;
  }
  select_isa(saved);
}

}  // namespace
}  // namespace dampbench
