// Batch evaluation is bit-identical whatever the thread count, the grain size, the candidate's position
// in the batch, or the batch it shares (docs/design.md, "Reproducibility principles").
#include "engine/evaluation/batch_evaluator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <tbb/task_arena.h>

#include "engine/model/bounds.hpp"
#include "engine/model/law_model.hpp"
#include "engine/model/parameter_law.hpp"
#include "engine/common/random.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

struct Fixture {
  const Model& model = find_model("fvd.gv_quadratic_elastic");
  Signals data;
  CandidateBatch batch;

  explicit Fixture(int count) {
    Dataset d = testing::two_sine_record(700);
    d.F_N = model.simulate(std::vector<double>{400, 7e5, 0.35, 3e6, 2e7}, prepare_signals(d));
    data = prepare_signals(d);
    const Bounds b = default_bounds(model);
    batch.resize(model.dim(), count);
    RandomStream rng(hash_key({5}));
    for (int i = 0; i < count; ++i)
      for (int j = 0; j < model.dim(); ++j) batch.at(i, j) = rng.uniform(b.lower[j], b.upper[j]);
  }

  std::vector<double> evaluate(const CandidateBatch& b, int threads, int grain) const {
    std::vector<double> out(b.count());
    tbb::task_arena arena(threads);
    arena.execute([&] { BatchEvaluator(model, data, grain).evaluate(b, Metric::of_abs, out); });
    return out;
  }
};

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

TEST(BatchEvaluator, OneAndTwoThreadsGiveTheSameBits) {
  const Fixture f(203);
  EXPECT_TRUE(same_bits(f.evaluate(f.batch, 1, 1), f.evaluate(f.batch, 2, 1)));
}

TEST(BatchEvaluator, GrainSizeDoesNotChangeResults) {
  const Fixture f(203);
  const auto reference = f.evaluate(f.batch, 2, 1);
  for (int grain : {2, 3, 7, 100}) EXPECT_TRUE(same_bits(reference, f.evaluate(f.batch, 2, grain))) << grain;
}

TEST(BatchEvaluator, CandidateAloneEqualsCandidateInBatch) {
  const Fixture f(41);
  const auto together = f.evaluate(f.batch, 2, 1);
  for (int i = 0; i < f.batch.count(); ++i) {
    CandidateBatch alone(f.model.dim(), 1);
    alone.set_candidate(0, f.batch.candidate(i));
    EXPECT_EQ(f.evaluate(alone, 1, 1)[0], together[i]) << "candidate " << i;
  }
}

TEST(BatchEvaluator, ReversedBatchGivesTheSameValues) {
  const Fixture f(50);
  CandidateBatch reversed(f.model.dim(), f.batch.count());
  for (int i = 0; i < f.batch.count(); ++i) reversed.set_candidate(f.batch.count() - 1 - i, f.batch.candidate(i));
  const auto a = f.evaluate(f.batch, 2, 1), b = f.evaluate(reversed, 2, 1);
  for (int i = 0; i < f.batch.count(); ++i) EXPECT_EQ(a[i], b[f.batch.count() - 1 - i]);
}

TEST(BatchEvaluator, BlownUpCandidateIsMaskedAndDoesNotTouchNeighbours) {
  Fixture f(20);
  const auto clean = f.evaluate(f.batch, 2, 1);
  f.batch.at(5, 1) = std::numeric_limits<double>::quiet_NaN();
  f.batch.at(6, 4) = std::numeric_limits<double>::infinity();
  const auto dirty = f.evaluate(f.batch, 2, 1);
  EXPECT_EQ(dirty[5], std::numeric_limits<double>::infinity());
  EXPECT_EQ(dirty[6], std::numeric_limits<double>::infinity());
  for (int i = 0; i < 20; ++i) {
    if (i == 5 || i == 6) continue;
    EXPECT_EQ(dirty[i], clean[i]) << i;
  }
}

TEST(BatchEvaluator, MetricOfSimulatedForceMatchesBatchPath) {
  const Fixture f(3);
  const auto batch_values = f.evaluate(f.batch, 1, 1);
  for (int i = 0; i < 3; ++i) {
    const auto F = f.model.simulate(f.batch.candidate(i), f.data);
    double integral = 0;
    for (std::size_t k = 0; k < F.size(); ++k) integral += f.data.w_trapz_s[k] * std::fabs(f.data.F_N[k] - F[k]);
    EXPECT_NEAR(batch_values[i], integral / (f.data.measured_std * f.data.duration_s), 1e-12 * batch_values[i]);
  }
}

}  // namespace dampbench

namespace dampbench {

// Every model's lane kernel against the plain scalar loop of the same law (Model::evaluate_scalar):
// the same sums up to rounding of the vector math library (libmvec lanes vs scalar libm).
TEST(BatchEvaluator, LaneKernelsMatchTheirScalarLoops) {
  for (const Model* m : all_models()) {
    const Dataset d = testing::two_sine_input(m->is_system(), 300);
    const Signals input = prepare_signals(d);
    const Bounds b = default_bounds(*m);
    CandidateBatch batch(m->dim(), 21);
    RandomStream rng(hash_key({17, hash_name(m->id())}));
    for (int i = 0; i < batch.count(); ++i)
      for (int j = 0; j < m->dim(); ++j)  // central half of the bounds: mostly well-behaved candidates
        batch.at(i, j) = b.lower[j] + (0.25 + 0.5 * rng.uniform()) * (b.upper[j] - b.lower[j]);
    Dataset with_force = d;
    testing::measured_output(with_force) = m->simulate(batch.candidate(0), input);
    for (double& f : testing::measured_output(with_force)) f = std::isfinite(f) ? f * 1.01 + 1.0 : 0.0;
    const Signals data = prepare_signals(with_force);
    std::vector<MetricSums> lanes(21), scalar(21);
    for (int first = 0; first < 21; first += kLanes) {
      const int count = std::min(kLanes, 21 - first);
      m->evaluate_block(batch, first, count, data, SumSet::every, lanes.data() + first);
      m->evaluate_scalar(batch, first, count, data, SumSet::every, scalar.data() + first);
    }
    for (int i = 0; i < 21; ++i) {
      const double a = lanes[i].abs_weighted, s = scalar[i].abs_weighted;
      if (std::isinf(a) || std::isinf(s) || std::isnan(a) || std::isnan(s)) {
        EXPECT_EQ(std::isfinite(a), std::isfinite(s)) << m->id() << " candidate " << i;
        continue;
      }
      EXPECT_NEAR(a, s, 1e-9 * std::fabs(s) + 1e-300) << m->id() << " candidate " << i;
    }
  }
}

// An evaluation of one metric computes only the sum it is finished from (SumSet): for every model and every
// metric, that sum has the bits it has when all five are computed, the others are NaN (so a metric finished from
// one of them is +inf, never a wrong number), and BatchEvaluator::evaluate equals the metric of evaluate_all.
TEST(BatchEvaluator, OneMetricsSumHasTheBitsOfAllSums) {
  const auto sum_of = [](const MetricSums& s, SumSet set) {
    switch (set) {
      case SumSet::abs_weighted: return s.abs_weighted;
      case SumSet::sq_weighted: return s.sq_weighted;
      case SumSet::abs: return s.abs;
      case SumSet::sq: return s.sq;
      case SumSet::abs_magnitude: return s.abs_magnitude;
      case SumSet::every: break;
    }
    return std::numeric_limits<double>::quiet_NaN();
  };
  const SumSet singles[] = {SumSet::abs_weighted, SumSet::sq_weighted, SumSet::abs, SumSet::sq, SumSet::abs_magnitude};
  for (const Model* m : all_models()) {
    const Dataset d = testing::two_sine_input(m->is_system(), 300);
    const Signals input = prepare_signals(d);
    Dataset with_force = d;
    const Bounds b = default_bounds(*m);
    CandidateBatch batch(m->dim(), 21);
    RandomStream rng(hash_key({5, hash_name(m->id())}));
    for (int i = 0; i < batch.count(); ++i)  // the whole box: masked candidates included
      for (int j = 0; j < m->dim(); ++j) batch.at(i, j) = b.lower[j] + rng.uniform() * (b.upper[j] - b.lower[j]);
    testing::measured_output(with_force) = m->simulate(batch.candidate(0), input);
    for (double& f : testing::measured_output(with_force)) f = std::isfinite(f) ? f * 1.01 + 1.0 : 0.0;
    const Signals data = prepare_signals(with_force);
    std::vector<MetricSums> every(21), one(21);
    for (int first = 0; first < 21; first += kLanes)
      m->evaluate_block(batch, first, std::min(kLanes, 21 - first), data, SumSet::every, every.data() + first);
    for (SumSet set : singles) {
      for (int first = 0; first < 21; first += kLanes)
        m->evaluate_block(batch, first, std::min(kLanes, 21 - first), data, set, one.data() + first);
      for (int i = 0; i < 21; ++i) {
        const bool masked = std::isinf(every[i].abs_weighted);
        for (SumSet other : singles) {
          const double got = sum_of(one[i], other);
          if (masked) EXPECT_TRUE(std::isinf(got)) << m->id() << " candidate " << i;
          else if (other == set) EXPECT_TRUE(same_bits({got}, {sum_of(every[i], set)})) << m->id() << " candidate " << i;
          else EXPECT_TRUE(std::isnan(got)) << m->id() << " candidate " << i;
        }
      }
    }
    const BatchEvaluator evaluator(*m, data);
    std::vector<MetricRow> rows(21);
    evaluator.evaluate_all(batch, rows);
    std::vector<double> values(21);
    for (int k = 0; k < kMetricCount; ++k) {
      evaluator.evaluate(batch, kAllMetrics[k], values);
      for (int i = 0; i < 21; ++i)
        EXPECT_TRUE(same_bits({values[i]}, {rows[i][k]})) << m->id() << " " << metric_name(kAllMetrics[k]) << " " << i;
    }
  }
}

// simulate_block (finite differences, identifiability: one lane block for up to kLanes candidates) gives each
// candidate the bits of simulate(), for every model, a full and a partial block, and a law model; a candidate
// that blows up is NaN and leaves its block-mates alone. Uses the whole default box, stiff corners included.
TEST(BatchEvaluator, SimulateBlockEqualsSimulateOfEachCandidate) {
  const Dataset d = testing::two_sine_record(300);
  const Signals input = prepare_signals(d);
  auto check = [&](const Model& m, const Signals& data, const CandidateBatch& batch) {
    const std::size_t n = data.size();
    for (int first = 0; first < batch.count(); first += kLanes) {
      const int count = std::min(kLanes, batch.count() - first);
      std::vector<double> block(static_cast<std::size_t>(count) * n);
      m.simulate_block(batch, first, count, data, block.data());
      for (int i = 0; i < count; ++i) {
        const std::vector<double> one = m.simulate(batch.candidate(first + i), data);
        const std::vector<double> lane(block.begin() + static_cast<std::ptrdiff_t>(i * n),
                                       block.begin() + static_cast<std::ptrdiff_t>((i + 1) * n));
        EXPECT_TRUE(same_bits(one, lane) || (std::isnan(one[0]) && std::isnan(lane[0])))
            << m.id() << " candidate " << first + i;
      }
    }
  };
  for (const Model* m : all_models()) {
    const Bounds b = default_bounds(*m);
    CandidateBatch batch(m->dim(), kLanes + 5);
    RandomStream rng(hash_key({23, hash_name(m->id())}));
    for (int i = 0; i < batch.count(); ++i)
      for (int j = 0; j < m->dim(); ++j) batch.at(i, j) = rng.uniform(b.lower[j], b.upper[j]);
    check(*m, m->is_system() ? prepare_signals(testing::two_sine_input(true, 300)) : input, batch);
  }
  // A law model: c0 and alpha linear in I on a record at I = 0.7.
  const LawModel law(find_model("mrd.bouc_wen"), parse_laws("c0=poly(I,1);alpha=poly(I,1)", "laws"));
  Dataset at = d;
  at.operating["I"] = 0.7;
  const Signals law_input = prepare_signals(at);
  const Bounds b = default_bounds(law);
  CandidateBatch batch(law.dim(), 7);
  RandomStream rng(hash_key({29}));
  for (int i = 0; i < batch.count(); ++i)
    for (int j = 0; j < law.dim(); ++j) batch.at(i, j) = rng.uniform(b.lower[j], b.upper[j]);
  check(law, law_input, batch);
}

// BatchEvaluator puts an ODE model's candidates into lane blocks by their stiffness (Model::lane_costs), so the
// lanes of a block take similar numbers of sub-steps: each candidate must still get, in its own place, the bits it
// gets alone, on both datasets (the order comes from the first one), for a law model too, and with the whole
// default box (stiff, soft and masked candidates mixed).
TEST(BatchEvaluator, CandidatesSortedByCostKeepTheirBitsAndPlaces) {
  auto with_force = [](Dataset d, double scale_N) {
    d.F_N.resize(d.x_m.size());
    for (std::size_t k = 0; k < d.F_N.size(); ++k) d.F_N[k] = scale_N * (d.v_m_s[k] + 40.0 * d.x_m[k]);
    return d;
  };
  auto check = [&](const Model& m, const Signals& first, const Signals& second, std::uint64_t seed) {
    const Bounds b = default_bounds(m);
    CandidateBatch batch(m.dim(), 3 * kLanes + 5);
    RandomStream rng(hash_key({seed, hash_name(m.id())}));
    for (int i = 0; i < batch.count(); ++i)
      for (int j = 0; j < m.dim(); ++j) batch.at(i, j) = rng.uniform(b.lower[j], b.upper[j]);
    // Most random candidates of a box take the fewest sub-steps: slot 1 gets the first further draw that costs
    // more than candidate 0, so that the batch is reordered whatever the draws.
    std::vector<double> cost(static_cast<std::size_t>(batch.count()));
    ASSERT_TRUE(m.lane_costs(batch, first, cost)) << m.id();
    CandidateBatch probe(m.dim(), 1);
    std::vector<double> probe_cost(1);
    for (int tries = 0; tries < 10000; ++tries) {
      for (int j = 0; j < m.dim(); ++j) probe.at(0, j) = rng.uniform(b.lower[j], b.upper[j]);
      m.lane_costs(probe, first, probe_cost);
      if (probe_cost[0] <= cost[0]) continue;
      batch.set_candidate(1, probe.candidate(0));
      break;
    }
    ASSERT_TRUE(m.lane_costs(batch, first, cost)) << m.id();
    ASSERT_FALSE(std::ranges::is_sorted(cost)) << m.id() << ": the batch would not be reordered";
    const BatchEvaluator evaluator(m, {&first, &second});
    std::vector<double> all(static_cast<std::size_t>(batch.count()));
    evaluator.evaluate(batch, Metric::nrmse, all);
    for (int i = 0; i < batch.count(); ++i) {
      CandidateBatch one(m.dim(), 1);
      one.set_candidate(0, batch.candidate(i));
      double alone = 0;
      evaluator.evaluate(one, Metric::nrmse, std::span<double>(&alone, 1));
      EXPECT_TRUE(std::memcmp(&alone, &all[static_cast<std::size_t>(i)], sizeof(double)) == 0)
          << m.id() << " candidate " << i << ": " << alone << " alone, " << all[static_cast<std::size_t>(i)];
    }
  };
  const Signals first = prepare_signals(with_force(testing::two_sine_record(300), 2000.0));
  const Signals second = prepare_signals(with_force(testing::two_sine_record(250, 400.0), 3000.0));
  for (const char* id : {"mrd.bouc_wen", "mrd.spencer", "mrd.spencer_voltage"}) check(find_model(id), first, second, 31);
  Dataset a = with_force(testing::two_sine_record(300), 2000.0), c = with_force(testing::two_sine_record(250, 400.0), 3000.0);
  a.operating["I"] = 0.2;
  c.operating["I"] = 0.9;
  // A=free: the published parametrization. Under the state gauge (A = β + γ) the candidates of the fixed default
  // box (β, γ up to 1e7, meant for |z| of a stroke) all cost the same; fits use the record-scaled box.
  const LawModel law(find_model("mrd.spencer"), parse_laws("c0=poly(I,1);alpha=poly(I,1);A=free", "laws"));
  check(law, prepare_signals(a), prepare_signals(c), 37);
  // Models whose candidates all cost the same are not reordered.
  std::vector<double> cost(4, -1.0);
  EXPECT_FALSE(find_model("fvd.gv_linear_elastic").lane_costs(CandidateBatch(5, 4), first, cost));
  EXPECT_EQ(cost[0], -1.0);
}

}  // namespace dampbench
