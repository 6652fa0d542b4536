#include "optimizers/ga/generation_draws.hpp"

#include <algorithm>

#include "optimizers/random_draws.hpp"

namespace dampbench {

void GenerationDraws::draw(std::uint64_t generation_key, int pairs, int children, int select_count,
                           int crossover_count, int mutate_count) {
  // Member i's key (run, g, i) is extend_key(generation_key, i): pair k's for k < pairs, child c's for c < children.
  member_keys_.resize(static_cast<std::size_t>(std::max(pairs, children)));
  member_keys(generation_key, member_keys_);
  const auto stream_draws = [&](int members, std::uint64_t name, int count, std::vector<double>& out) {
    keys_.assign(member_keys_.begin(), member_keys_.begin() + members);
    extend_keys(keys_, name);
    first_uniforms(keys_, count, out, scratch_);
  };
  stream_draws(pairs, kSelectStream, select_count, select_);
  stream_draws(pairs, kCrossoverStream, crossover_count, crossover_);
  stream_draws(children, kMutateStream, mutate_count, mutate_);
  select_count_ = select_count;
  crossover_count_ = crossover_count;
  mutate_count_ = mutate_count;
}

}  // namespace dampbench
