#include "optimizers/narrowing/narrowing.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/random.hpp"

namespace dampbench {

Bounds wide_bounds(const Model& model, double half_width) {
  return {std::vector<double>(model.dim(), -half_width), std::vector<double>(model.dim(), half_width)};
}

NarrowingResult narrow_bounds(const Model& model, const std::vector<const Signals*>& conditions, Bounds start,
                              const OptimizerSpec& inner, int rounds, IdentificationSettings settings) {
  if (rounds < 1) throw InputError(fmt::format("narrow: rounds must be at least 1, got {}", rounds));
  if (conditions.empty()) throw InputError("narrow: give at least one condition (dataset)");
  for (const Signals* c : conditions)
    if (!c) throw InputError("narrow: a condition is missing (null dataset)");
  validate_bounds(start, model);
  const OptimizerFactory factory = make_optimizer_factory(inner);

  NarrowingResult result;
  Bounds bounds = std::move(start);
  const std::uint64_t base_key = settings.task_key;
  result.stop_reason = "rounds";
  for (int k = 1; k <= rounds; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    NarrowingRound round;
    round.round = k;
    round.bounds = bounds;
    Bounds next{std::vector<double>(model.dim(), std::numeric_limits<double>::infinity()),
                std::vector<double>(model.dim(), -std::numeric_limits<double>::infinity())};
    for (std::size_t c = 0; c < conditions.size(); ++c) {
      settings.task_key = hash_key({base_key, hash_name("narrow"), static_cast<std::uint64_t>(k), c});
      const Identification id = identify(model, *conditions[c], bounds, factory, settings);
      NarrowingCondition cond;
      cond.name = conditions[c]->name;
      for (const RunResult& run : id.runs) {
        cond.finite_runs += std::isfinite(run.best_value) ? 1 : 0;
        cond.evaluations += run.evaluations;
      }
      const RunResult& best = id.runs[id.best_run()];
      cond.best_value = best.best_value;
      cond.failed = !std::isfinite(best.best_value);
      if (!cond.failed) {
        cond.best_params = best.best_params;
        for (int j = 0; j < model.dim(); ++j) {
          next.lower[j] = std::min(next.lower[j], best.best_params[j]);
          next.upper[j] = std::max(next.upper[j], best.best_params[j]);
        }
      }
      round.failed_conditions += cond.failed ? 1 : 0;
      round.conditions.push_back(std::move(cond));
    }
    const bool all_failed = round.failed_conditions == static_cast<int>(conditions.size());
    round.next = all_failed ? bounds : next;
    round.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    bounds = round.next;
    result.rounds.push_back(std::move(round));
    if (all_failed) {
      result.stop_reason = fmt::format("round {}: every condition failed (all runs +inf); bounds kept", k);
      break;
    }
  }
  result.final_bounds = bounds;
  return result;
}

}  // namespace dampbench
