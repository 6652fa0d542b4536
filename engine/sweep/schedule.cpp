#include "engine/sweep/schedule.hpp"

#include <algorithm>
#include <charconv>
#include <numeric>
#include <queue>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/fit/law_selection.hpp"
#include "engine/fit/resolve_model.hpp"

namespace dampbench::sweep {

std::string Shard::text() const { return whole() ? std::string() : fmt::format("{}/{}", index + 1, count); }

Shard parse_shard(std::string_view text, std::string_view what) {
  const auto slash = text.find('/');
  int i = 0, n = 0;
  auto number = [](std::string_view s, int& v) {
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && end == s.data() + s.size() && !s.empty();
  };
  if (slash == std::string_view::npos || !number(text.substr(0, slash), i) || !number(text.substr(slash + 1), n) ||
      n < 1 || i < 1 || i > n || n > kMaxShards)
    throw InputError(fmt::format("{}: expected i/n with 1 <= i <= n <= {} (e.g. 2/8), got '{}'", what, kMaxShards, text));
  return {i - 1, n};
}

double estimated_cost(const Plan& plan, const GroupRef& g) {
  const PartPlan& part = plan.parts()[g.part];
  const OptimizerEntry& opt = part.spec->optimizers[g.optimizer];
  double evaluations = static_cast<double>(opt.spec.population) * (opt.spec.iterations + 1);
  if (opt.budget.max_evaluations > 0) evaluations = std::min(evaluations, static_cast<double>(opt.budget.max_evaluations));
  double samples = 0;
  for (int d : part.splits[g.split].fitsets[g.fitset].fit) samples += static_cast<double>(part.datasets[d].signals.size());
  samples = std::max(samples, 1.0);
  const ModelSpec& entry = part.spec->models[g.model];
  const int dim = part.models[g.model].model->dim();
  const double one_fit = g.runs * evaluations * samples * dim;
  // laws = "auto": each record's own fit, the choice's simulations, and the joint fit of a law model of about twice
  // the base model's coefficients.
  if (chooses_laws(entry)) return 3 * one_fit + law_choice_simulations(dim) * samples * dim;
  if (entry.start == "per-file") return 2 * one_fit;  // each record's own fit, then the joint fit
  if (entry.narrow) return (entry.narrow->rounds + 1) * one_fit;  // each round's per-record fits, then the joint fit
  return one_fit;
}

namespace {
/// Every group's cost, and the group numbers in decreasing cost (ties: lower number first).
struct CostOrder {
  std::vector<double> cost;
  std::vector<long long> order;
};

CostOrder by_decreasing_cost(const Plan& plan) {
  CostOrder c;
  c.cost.resize(static_cast<std::size_t>(plan.groups()));
  for (long long i = 0; i < plan.groups(); ++i) c.cost[static_cast<std::size_t>(i)] = estimated_cost(plan, plan.group(i));
  c.order.resize(c.cost.size());
  std::iota(c.order.begin(), c.order.end(), 0LL);
  std::stable_sort(c.order.begin(), c.order.end(), [&](long long a, long long b) {
    return c.cost[static_cast<std::size_t>(a)] > c.cost[static_cast<std::size_t>(b)];
  });
  return c;
}

/// The groups of `shard`: each group in decreasing cost to the least loaded shard (lowest number on ties).
std::vector<char> members(const CostOrder& c, const Shard& shard) {
  std::vector<char> in(c.cost.size(), shard.whole() ? 1 : 0);
  if (shard.whole()) return in;
  using Load = std::pair<double, int>;  // (work so far, shard) in a min-heap
  std::priority_queue<Load, std::vector<Load>, std::greater<>> load;
  for (int s = 0; s < shard.count; ++s) load.emplace(0.0, s);
  for (long long i : c.order) {
    auto [work, s] = load.top();
    load.pop();
    if (s == shard.index) in[static_cast<std::size_t>(i)] = 1;
    load.emplace(work + c.cost[static_cast<std::size_t>(i)], s);
  }
  return in;
}
}  // namespace

std::vector<char> shard_groups(const Plan& plan, const Shard& shard) {
  if (shard.whole()) return std::vector<char>(static_cast<std::size_t>(plan.groups()), 1);
  return members(by_decreasing_cost(plan), shard);
}

std::vector<long long> schedule(const Plan& plan, const std::vector<char>& done, const Shard& shard) {
  const CostOrder c = by_decreasing_cost(plan);  // one decoding and sort serves the shard and the order
  const std::vector<char> in = members(c, shard);
  std::vector<long long> todo;
  for (long long i : c.order)
    if (in[static_cast<std::size_t>(i)] && !done[static_cast<std::size_t>(i)]) todo.push_back(i);
  return todo;
}

}  // namespace dampbench::sweep
