// optimizers/ga/generation_draws.hpp: each row is the first draws of the stream the GA's header names
// (optimizers/ga/genetic.hpp), (run_key, g, k, "select"), (run_key, g, k, "crossover") and (run_key, g, c, "mutate"),
// as RandomStream gives them: the bits of every GA fit rest on this.
#include "optimizers/ga/generation_draws.hpp"

#include <gtest/gtest.h>

#include <cstdint>

#include "engine/common/random.hpp"
#include "engine/kernels/isa.hpp"

namespace dampbench {
namespace {

TEST(GenerationDraws, RowsAreTheNamedStreamsDraws) {
  const Isa saved = active_isa();
  GenerationDraws draws;  // one object over several shapes, as a run reuses it every generation
  for (const Isa isa : supported_isas()) {
    select_isa(isa);
    struct Shape {
      int pairs, children, select, crossover, mutate;
    };
    for (const Shape& sh : {Shape{25, 50, 4, 13, 8}, Shape{16, 31, 62, 25, 16}, Shape{3, 5, 2, 70, 1}}) {
      const std::uint64_t run_key = hash_key({9, static_cast<std::uint64_t>(sh.pairs)}), g = 7;
      draws.draw(hash_key({run_key, g}), sh.pairs, sh.children, sh.select, sh.crossover, sh.mutate);
      for (int k = 0; k < sh.pairs; ++k) {
        const auto member = static_cast<std::uint64_t>(k);
        RandomStream select(hash_key({run_key, g, member, hash_name("select")}));
        RandomStream crossover(hash_key({run_key, g, member, hash_name("crossover")}));
        ASSERT_EQ(draws.select(k).size(), static_cast<std::size_t>(sh.select));
        ASSERT_EQ(draws.crossover(k).size(), static_cast<std::size_t>(sh.crossover));
        for (const double d : draws.select(k)) EXPECT_EQ(d, select.uniform()) << isa_name(isa) << " pair " << k;
        for (const double d : draws.crossover(k)) EXPECT_EQ(d, crossover.uniform()) << isa_name(isa) << " pair " << k;
      }
      for (int c = 0; c < sh.children; ++c) {
        RandomStream mutate(hash_key({run_key, g, static_cast<std::uint64_t>(c), hash_name("mutate")}));
        ASSERT_EQ(draws.mutate(c).size(), static_cast<std::size_t>(sh.mutate));
        for (const double d : draws.mutate(c)) EXPECT_EQ(d, mutate.uniform()) << isa_name(isa) << " child " << c;
      }
    }
  }
  select_isa(saved);
}

}  // namespace
}  // namespace dampbench
