// A law model's box and start from the mfm paper's bound narrowing (engine/fit/record_narrowing.hpp): the
// per-record fits of a known Bingham damper give back its laws, and the box follows the header's rules exactly.
#include "engine/fit/record_narrowing.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/common/error.hpp"
#include "engine/model/law_model.hpp"
#include "engine/record/excitation.hpp"
#include "models/registry.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

// Bingham with f_c = 150 + 300·I [N], c0 = 2500 N·s/m, f0 = −5 N: the truth of the records below.
const std::vector<double> kTruth = {150.0, 300.0, 2500.0, -5.0};
const char* kLaws = "f_c=poly(I,1)";

std::vector<Signals> bingham_records(const std::vector<double>& currents) {
  const LawModel truth(find_model("mrd.bingham"), parse_laws(kLaws, "--laws"));
  std::vector<Signals> out;
  for (double I : currents) {
    Dataset d = make_sine({0.01, 1, 0, 2, 200});
    d.name = "I" + std::to_string(I);
    d.operating["I"] = I;
    d.F_N = truth.simulate(kTruth, prepare_signals(d));
    out.push_back(prepare_signals(d));
  }
  return out;
}

struct Narrowed {
  NarrowedStart start;
  ResolvedModel law_model;
};

Narrowed narrow(const std::vector<Signals>& records, const std::string& laws = kLaws, const std::string& from = "default") {
  ModelChoice choice;
  choice.model = "mrd.bingham";
  choice.laws = laws;
  Narrowed n{{}, resolve_model(choice)};
  std::vector<const Signals*> pointers;
  for (const Signals& r : records) pointers.push_back(&r);
  IdentificationSettings s;
  s.runs = 2;
  s.seed = 7;
  s.metric = Metric::nrmse;
  n.start = narrowed_start(choice, *n.law_model.model, pointers, {"ga-lm", 20, 10}, s, {2, from});
  return n;
}

}  // namespace

TEST(RecordNarrowing, PerCurrentFitsGiveBackTheLawsAndTheBoxFollowsTheirRanges) {
  const auto records = bingham_records({0.0, 0.5, 1.0});
  const Narrowed n = narrow(records);
  const NarrowingResult& r = n.start.narrowing;
  ASSERT_EQ(r.rounds.size(), 2u);
  for (const NarrowingRound& round : r.rounds) EXPECT_EQ(round.failed_conditions, 0);
  // The base model's parameters: f_c, c0, f0 (the law's f_c a free constant per record). Each current's fit is
  // exact on noise-free records, so the last round's f_c are 150, 300, 450.
  const Bounds& fin = r.final_bounds;
  ASSERT_EQ(fin.dim(), 3);
  EXPECT_NEAR(fin.lower[0], 150.0, 1e-3);
  EXPECT_NEAR(fin.upper[0], 450.0, 1e-3);
  // The law model's box (f_c_I0, f_c_I1, c0, f0) by the header's rules, currents from 0 to 1 A.
  const Bounds& box = n.start.box;
  ASSERT_EQ(box.dim(), 4);
  EXPECT_EQ(box.lower[0], fin.lower[0]);  // a = p(0): the range itself
  EXPECT_EQ(box.upper[0], fin.upper[0]);
  EXPECT_EQ(box.upper[1], (fin.upper[0] - fin.lower[0]) / 1.0);  // |b| <= width / (1 A - 0 A)
  EXPECT_EQ(box.lower[1], -box.upper[1]);
  for (int j : {1, 2}) {  // shared parameters: their ranges
    EXPECT_EQ(box.lower[j + 1], fin.lower[j]);
    EXPECT_EQ(box.upper[j + 1], fin.upper[j]);
  }
  // The start: the laws fitted to the per-current fits, the truth.
  ASSERT_EQ(n.start.start.size(), 4u);
  for (std::size_t k = 0; k < kTruth.size(); ++k)
    EXPECT_NEAR(n.start.start[k], kTruth[k], 1e-3 * std::abs(kTruth[k])) << k;
  EXPECT_GT(n.start.effort.evaluations, 0);
  EXPECT_NE(n.start.summary.find("bounds narrowed over 3 records in 2 rounds (failed records per round: 0, 0;"),
            std::string::npos)
      << n.start.summary;
}

TEST(RecordNarrowing, ALawOverCurrentsAwayFromZeroWidensItsConstantByTheSlope) {
  const auto records = bingham_records({1.0, 3.0});
  const Narrowed n = narrow(records);
  const Bounds& fin = n.start.narrowing.final_bounds;
  const Bounds& box = n.start.box;
  // f_c from 450 to 1050 between 1 and 3 A: |b| <= 600 / 2 = 300, a = p(1) - b·1 within [450 - 300, 1050 + 300].
  const double slope = (fin.upper[0] - fin.lower[0]) / (3.0 - 1.0);
  EXPECT_NEAR(slope, 300.0, 1e-3);
  EXPECT_EQ(box.upper[1], slope);
  EXPECT_EQ(box.lower[0], fin.lower[0] - slope * 1.0);
  EXPECT_EQ(box.upper[0], fin.upper[0] + slope * 1.0);
  EXPECT_NEAR(n.start.start[0], kTruth[0], 1e-3 * kTruth[0]);  // the line through both currents' fits
  EXPECT_NEAR(n.start.start[1], kTruth[1], 1e-3 * kTruth[1]);
}

TEST(RecordNarrowing, LawsWithoutABoxAndRecordsWithoutASpreadAreRefused) {
  const auto records = bingham_records({0.0, 1.0});
  EXPECT_EQ(testing::error_of([&] { narrow(records, "f_c=power(I)"); }),
            "narrow: the law f_c=power(I) has no box from a narrowed range (those that have one: free, poly(VAR,0), "
            "poly(VAR,1))");
  const auto one_current = bingham_records({0.5, 0.5});
  EXPECT_EQ(testing::error_of([&] { narrow(one_current); }),
            "narrow: f_c's law is linear in I, which is 0.5 on every record: the records bound no slope");
  EXPECT_EQ(testing::error_of([&] { narrow(records, kLaws, "paper"); }),
            "narrow: from: expected \"default\" or \"wide\", got 'paper'");
}

}  // namespace dampbench
