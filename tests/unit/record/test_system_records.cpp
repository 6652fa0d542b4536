// System records (t, y, u: a structure driven by the force u, its displacement y out): loading, units, the
// columns they refuse, and the statistics that normalise their metrics.
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "engine/common/error.hpp"
#include "engine/record/csv_loader.hpp"
#include "engine/record/signals.hpp"
#include "tests/test_support.hpp"

namespace dampbench {
namespace {

Dataset parse_system(const std::string& text, bool require_output = true) {
  std::istringstream in(text);
  CsvOptions options;
  options.require_force = require_output;
  options.min_samples = 4;
  return parse_csv(in, "bw.csv", options);
}

const std::string kRecord = "t[s],y[mm],u[kN]\n0,0,0\n0.5,1,0.002\n1,-2,0.001\n1.5,3,-0.004\n2,0,0\n";

TEST(SystemRecords, LoadInSiWithoutRigColumns) {
  const Dataset d = parse_system(kRecord);
  ASSERT_TRUE(d.is_system());
  EXPECT_EQ(d.y_m, (std::vector<double>{0, 1e-3, -2e-3, 3e-3, 0}));
  EXPECT_EQ(d.u_N, (std::vector<double>{0, 2, 1, -4, 0}));
  EXPECT_TRUE(d.x_m.empty());
  EXPECT_TRUE(d.F_N.empty());
  EXPECT_EQ(&d.measured(), &d.y_m);
  EXPECT_FALSE(d.periodic_input);
}

TEST(SystemRecords, MeasuredStatisticsAreTheDisplacements) {
  const Signals s = prepare_signals(parse_system(kRecord));
  EXPECT_DOUBLE_EQ(s.measured_max_abs, 3e-3);
  EXPECT_DOUBLE_EQ(s.measured_sum_sq, 14e-6);  // 1 + 4 + 9 mm²
  EXPECT_TRUE(s.sgn_x.empty());
  EXPECT_EQ(s.law_variables.count("amp"), 0u);  // no stroke to estimate it from
}

TEST(SystemRecords, AnInputAloneLoadsWhenNoOutputIsNeeded) {
  const Dataset d = parse_system("t,u\n0,1\n1,2\n2,3\n3,4\n", false);
  EXPECT_TRUE(d.is_system());
  EXPECT_FALSE(d.has_measured());
}

TEST(SystemRecords, MissingOutputAndMixedKindsAreRefused) {
  EXPECT_EQ(testing::error_of([] { parse_system("t,u\n0,1\n1,2\n2,3\n3,4\n"); }),
            "bw.csv: missing column 'y' (columns found: t, u)");
  const std::string mixed = testing::error_of([] { parse_system("t,x,u\n0,0,1\n1,0,2\n2,0,3\n3,0,4\n"); });
  EXPECT_NE(mixed.find("bw.csv: column 'x' with a force input u"), std::string::npos) << mixed;
  EXPECT_NE(mixed.find("t,y,u (force u in, displacement y out: a system)"), std::string::npos) << mixed;
}

TEST(SystemRecords, UniformSamplingIsRequiredBySystemModels) {
  check_uniform_sampling(parse_system(kRecord));
  const std::string message =
      testing::error_of([] { check_uniform_sampling(parse_system("t,y,u\n0,0,0\n1,0,1\n2.5,0,2\n3.5,0,3\n")); });
  EXPECT_EQ(message.rfind("record 'bw': sample 1 is at 1 s, -0.143 steps from the uniform grid of 1.16667 s", 0), 0u)
      << message;
}

}  // namespace
}  // namespace dampbench
