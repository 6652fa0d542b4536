#include "engine/common/random.hpp"

#include <gtest/gtest.h>

#include <set>

namespace dampbench {

TEST(RandomStream, SameKeySameSequence) {
  RandomStream a(hash_key({1, 2, 3})), b(hash_key({1, 2, 3}));
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.next_u64(), b.next_u64());
}

TEST(RandomStream, KeyPartsAreOrdered) {
  EXPECT_NE(hash_key({1, 2}), hash_key({2, 1}));
  EXPECT_NE(hash_key({0}), hash_key({0, 0}));
  EXPECT_NE(hash_name("fvd.linear_viscous"), hash_name("fvd.generalized_viscous"));
}

TEST(RandomStream, NeighbouringKeysGiveDifferentStreams) {
  std::set<std::uint64_t> first_draws;
  for (std::uint64_t member = 0; member < 1000; ++member)
    first_draws.insert(RandomStream(hash_key({7, 0, member})).next_u64());
  EXPECT_EQ(first_draws.size(), 1000u);
}

TEST(RandomStream, UniformMomentsMatch) {
  RandomStream rng(hash_key({42}));
  const int n = 200000;
  double sum = 0, sum_sq = 0;
  for (int i = 0; i < n; ++i) {
    const double u = rng.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum_sq += u * u;
  }
  // U[0,1): mean 1/2, variance 1/12; 5 standard errors.
  EXPECT_NEAR(sum / n, 0.5, 5 * std::sqrt(1.0 / 12 / n));
  EXPECT_NEAR(sum_sq / n - (sum / n) * (sum / n), 1.0 / 12, 0.002);
}

TEST(RandomStream, NormalMomentsMatch) {
  RandomStream rng(hash_key({9}));
  const int n = 200000;
  double sum = 0, sum_sq = 0;
  for (int i = 0; i < n; ++i) {
    const double z = rng.normal();
    sum += z;
    sum_sq += z * z;
  }
  EXPECT_NEAR(sum / n, 0.0, 5 / std::sqrt(double(n)));
  EXPECT_NEAR(sum_sq / n, 1.0, 0.02);
}

TEST(RandomStream, ShortcutsGiveTheDefinedNumbers) {
  // Draw k of a stream is mix64(key ^ mix64(k)), whether mix64(k) comes from the table of the first draws or not.
  const std::uint64_t key = hash_key({7, 11, 13});
  RandomStream rng(key);
  for (std::uint64_t k = 0; k < 200; ++k) EXPECT_EQ(rng.next_u64(), mix64(key ^ mix64(k))) << "draw " << k;
  // A key extended part by part is the key of all the parts.
  EXPECT_EQ(extend_key(hash_key({7, 11}), 13), key);
  EXPECT_EQ(extend_key(extend_key(hash_key({7}), 11), 13), key);
  EXPECT_NE(extend_key(hash_key({7, 13}), 11), key);
}

TEST(RandomStream, PeekAndSkipGiveTheDrawsUniformWouldGive) {
  // peek_uniform(a) is draw counter + a as a uniform, (bits >> 11)·2^-53, without moving on; skip(n) moves on by
  // n draws. Across the end of the table of first draws (64) too.
  const std::uint64_t key = hash_key({3, 5});
  const auto uniform_at = [&](std::uint64_t k) { return static_cast<double>(mix64(key ^ mix64(k)) >> 11) * 0x1.0p-53; };
  RandomStream rng(key);
  std::uint64_t at = 0;
  for (std::uint64_t n : {0, 1, 2, 3, 57, 1, 2, 40}) {
    for (std::uint64_t a = 0; a < 4; ++a) EXPECT_EQ(rng.peek_uniform(a), uniform_at(at + a)) << "draw " << at + a;
    rng.skip(n);
    at += n;
  }
  EXPECT_EQ(rng.uniform(), uniform_at(at));
}

}  // namespace dampbench
