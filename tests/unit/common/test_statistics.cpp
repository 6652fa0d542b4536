#include "engine/common/statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace dampbench {

TEST(Summarize, HandComputedValues) {
  const std::vector<double> v{1, 2, 3, 4};
  const Summary s = summarize(v);
  EXPECT_EQ(s.count, 4);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.min, 1);
  EXPECT_DOUBLE_EQ(s.max, 4);
  // sample variance: (2.25 + 0.25 + 0.25 + 2.25) / 3 = 5/3
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(5.0 / 3.0));
}

TEST(Summarize, SingleValueHasZeroStd) {
  const std::vector<double> v{0.3};
  const Summary s = summarize(v);
  EXPECT_DOUBLE_EQ(s.mean, 0.3);
  EXPECT_EQ(s.std, 0.0);
}

TEST(Summarize, FailedRunIsNeverAveragedAway) {
  const std::vector<double> v{1, std::numeric_limits<double>::infinity(), 3};
  const Summary s = summarize(v);
  EXPECT_TRUE(std::isinf(s.mean));
  EXPECT_TRUE(std::isinf(s.std));
  EXPECT_FALSE(std::isnan(s.mean));
}

}  // namespace dampbench
