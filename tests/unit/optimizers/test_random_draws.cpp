// optimizers/random_draws.hpp: the vector loops give, at every vector level, exactly the numbers RandomStream and
// extend_key define (engine/common/random.hpp), for any count (whole vectors, remainders, past the table of mixed
// counters).
#include "optimizers/random_draws.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "engine/common/random.hpp"
#include "engine/kernels/isa.hpp"

namespace dampbench {
namespace {

TEST(RandomDraws, MixEachExtendKeysAndMemberKeysAreMix64AndExtendKey) {
  const Isa saved = active_isa();
  for (const Isa isa : supported_isas()) {
    select_isa(isa);
    for (std::size_t n : {0, 1, 7, 8, 9, 33}) {
      std::vector<std::uint64_t> x(n), keys(n);
      for (std::size_t i = 0; i < n; ++i) x[i] = keys[i] = hash_key({i, 3}) ^ (i << 60);
      const std::vector<std::uint64_t> before = x;
      mix_each(x);
      extend_keys(keys, 0xfeedULL);
      std::vector<std::uint64_t> members(n);
      member_keys(hash_key({0x1234ULL}), members);
      for (std::size_t i = 0; i < n; ++i) {
        EXPECT_EQ(x[i], mix64(before[i])) << isa_name(isa) << " n " << n << " i " << i;
        EXPECT_EQ(keys[i], extend_key(before[i], 0xfeedULL)) << isa_name(isa) << " n " << n << " i " << i;
        EXPECT_EQ(members[i], hash_key({0x1234ULL, i})) << isa_name(isa) << " n " << n << " i " << i;
      }
    }
  }
  select_isa(saved);
}

TEST(RandomDraws, FirstUniformsAreEachStreamsDraws) {
  const Isa saved = active_isa();
  std::vector<double> out;               // reused over the shapes, as GenerationDraws reuses its storage
  std::vector<std::uint64_t> scratch;
  for (const Isa isa : supported_isas()) {
    select_isa(isa);
    for (const int draws : {1, 3, 13, 70, 0}) {  // 70: past the 64 precomputed counters
      std::vector<std::uint64_t> keys;
      for (std::uint64_t s = 0; s < 11; ++s) keys.push_back(hash_key({5, s}));
      first_uniforms(keys, draws, out, scratch);
      ASSERT_EQ(out.size(), keys.size() * static_cast<std::size_t>(draws));
      for (std::size_t s = 0; s < keys.size(); ++s) {
        RandomStream rng(keys[s]);
        for (int d = 0; d < draws; ++d)
          EXPECT_EQ(out[s * static_cast<std::size_t>(draws) + static_cast<std::size_t>(d)], rng.uniform())
              << isa_name(isa) << " stream " << s << " draw " << d;
      }
    }
  }
  first_uniforms({}, 5, out, scratch);  // no streams
  EXPECT_TRUE(out.empty());
  select_isa(saved);
}

// The normals are normal()'s (the same uniforms in the same order, the same formula) up to the last bits of the vector
// log and cos: within 1e-14 relative (libmvec's functions are within 4 ulp), or 1e-15 absolute near a zero of cos.
TEST(RandomDraws, FirstNormalsAreEachStreamsNormals) {
  const Isa saved = active_isa();
  std::vector<double> out, uniforms;
  std::vector<std::uint64_t> scratch;
  for (const Isa isa : supported_isas()) {
    select_isa(isa);
    for (const int count : {1, 5, 9, 40, 0}) {  // 40: 80 uniforms, past the 64 precomputed counters
      std::vector<std::uint64_t> keys;
      for (std::uint64_t s = 0; s < 7; ++s) keys.push_back(hash_key({9, s}));
      first_normals(keys, count, out, uniforms, scratch);
      ASSERT_EQ(out.size(), keys.size() * static_cast<std::size_t>(count));
      for (std::size_t s = 0; s < keys.size(); ++s) {
        RandomStream rng(keys[s]);
        for (int i = 0; i < count; ++i) {
          const double expected = rng.normal();
          EXPECT_NEAR(out[s * static_cast<std::size_t>(count) + static_cast<std::size_t>(i)], expected,
                      1e-14 * std::abs(expected) + 1e-15)
              << isa_name(isa) << " stream " << s << " normal " << i;
        }
      }
    }
  }
  select_isa(saved);
}

}  // namespace
}  // namespace dampbench
