#include "engine/fit/auto_budget.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/random.hpp"
#include "engine/fit/fit_defaults.hpp"
#include "engine/identification/convergence.hpp"
#include "optimizers/cmaes/cmaes.hpp"

namespace dampbench {

std::string AutoBudgetReport::summary() const {
  std::string sizes;
  for (int i : iterations) sizes += fmt::format("{}{}", sizes.empty() ? "" : ", ", i);
  const std::string gain =
      std::isnan(last_restart_rel)       ? "every run of the last restart failed"
      : !std::isfinite(last_restart_rel) ? "no restart yet"
      : last_restart_rel <= 0
          ? fmt::format("the last restart improved the best by {:.2g} %", -100 * last_restart_rel)
          : fmt::format("the last restart ended {:.2g} % above the best", 100 * last_restart_rel);
  const std::string label = second_opinion_label();
  const std::string second =
      label.empty() ? ""
      : std::isnan(second_opinion_rel)
          ? fmt::format("; every run of a second opinion ({}) failed", label)
      : second_opinion_lower
          ? fmt::format("; a second opinion ({}) found {:.2g} % lower: the runs share a basin that is not the lowest",
                        label, -100 * second_opinion_rel)
          : fmt::format("; a second opinion ({}) ended {:.2g} % {} the best", label,
                        100 * std::abs(second_opinion_rel), second_opinion_rel < 0 ? "below" : "above");
  const std::string why = stop == "converged" ? "converged, " + gain
                          : stop == "time cap"
                              ? "stopped by the time cap (not reproducible bit for bit); " + gain
                              : "stopped at the cap before converging; " + gain;
  return fmt::format("{} round{} (iterations {}), {} of {} evaluations: {}{}", iterations.size(),
                     iterations.size() == 1 ? "" : "s", sizes, evaluations, cap, why, second);
}

std::string AutoBudgetReport::second_opinion_label() const {
  if (!second_opinion_optimizer) return "";
  const auto global = second_opinion_optimizer->settings.find("global");
  return second_opinion_optimizer->name +
         (global == second_opinion_optimizer->settings.end() ? "" : "+" + global->second);
}

bool stopped_before_converging(std::string_view summary) {
  return summary.find(" evaluations: stopped ") != std::string_view::npos;
}

long long default_cap(long long round0, long long second_opinion) { return 64 * round0 + second_opinion; }

bool restart_confirms(double before, double restart) {
  if (!std::isfinite(before) || !std::isfinite(restart)) return false;
  return std::abs(restart - before) <= kRestartRel * std::min(std::abs(before), std::abs(restart)) +
                                           ConvergenceRule{}.abs_tol;
}

OptimizerSpec second_opinion(const Model& model, const OptimizerSpec& optimizer) {
  const auto global = optimizer.settings.find("global");
  const bool ga_lm_with_ga = optimizer.name == "ga-lm" && (global == optimizer.settings.end() || global->second == "ga");
  const bool states = model.has_internal_states();
  const std::string name = !states && optimizer.name != "de" ? "de" : "ga-lm";
  const FitPlan plan = fit_plan(model, name, std::nullopt, std::nullopt, std::nullopt);
  OptimizerSpec s{name, plan.population, plan.iterations};
  if (name == "ga-lm" && ga_lm_with_ga) s.settings["global"] = "cmaes";
  return s;
}

int second_opinion_runs(const Model& model, int runs) {
  return std::max(runs, fit_plan(model, std::nullopt, std::nullopt, std::nullopt, std::nullopt).runs);
}

int round_iterations(const OptimizerSpec& optimizer, int round) { return optimizer.iterations << round; }

namespace {

/// The chain's best-so-far: its history's last value, or a better best from a local phase after it.
double chain_best(const RunResult& chain) {
  const double last = chain.trace.empty() ? std::numeric_limits<double>::infinity() : chain.trace.back();
  return std::isnan(chain.best_value) ? last : std::min(last, chain.best_value);
}

/// Makes the chain's history end where the chain ends, so that a local phase's gain after its last population
/// iteration is not lost when the next round's history is appended (convergence.cpp's improvement_points).
void close_history(RunResult& chain) {
  const double best = chain_best(chain);
  if (chain.trace.empty() || best < chain.trace.back() || chain.trace_evaluations.back() != chain.evaluations) {
    chain.trace.push_back(best);
    chain.trace_evaluations.push_back(chain.evaluations);
  }
}

void append_run(RunResult& chain, const RunResult& next) {
  close_history(chain);
  const double before = chain_best(chain);
  const long long offset = chain.evaluations;
  for (std::size_t i = 0; i < next.trace.size(); ++i) {
    chain.trace.push_back(std::min(before, next.trace[i]));
    chain.trace_evaluations.push_back(offset + next.trace_evaluations[i]);
  }
  chain.evaluations += next.evaluations;
  chain.wall_time_s += next.wall_time_s;
  chain.stop_reason = next.stop_reason;
  const bool better = std::isnan(chain.best_value) ? !std::isnan(next.best_value) : next.best_value < chain.best_value;
  if (better) {
    chain.best_params = next.best_params;
    chain.best_value = next.best_value;
    chain.best_metrics = next.best_metrics;
    chain.at_local_optimum = next.at_local_optimum;
  }
}

int free_parameters(const Bounds& bounds) {
  int n = 0;
  for (int i = 0; i < bounds.dim(); ++i) n += bounds.lower[i] < bounds.upper[i];
  return n;
}

/// The chains' best value (+inf when no chain has a finite one).
double best_of(const Identification& chains) {
  double best = std::numeric_limits<double>::infinity();
  for (const RunResult& r : chains.runs) best = std::min(best, chain_best(r));
  return best;
}

/// The second opinion's streams: keyed apart from every round's (hash_key({task, k}) for small k).
constexpr std::uint64_t kSecondOpinionKey = hash_name("auto-budget second opinion");

/// `difference` relative to `best` (guarded against a best of 0).
double relative_to(double difference, double best) {
  return difference / std::max(std::abs(best), std::numeric_limits<double>::min());
}

/// The second opinion's best against the chains' best `best`: relative, and whether it is lower by more than a
/// restart could confirm.
void compare_second_opinion(AutoBudgetReport& report, double best) {
  report.second_opinion_rel = std::isfinite(report.second_opinion_best)
                                  ? relative_to(report.second_opinion_best - best, best)
                                  : std::numeric_limits<double>::quiet_NaN();
  report.second_opinion_lower = report.second_opinion_best < best && !restart_confirms(best, report.second_opinion_best);
}

/// The smaller of a rule's limit and `limit`, where 0 switches the rule off.
template <class T>
T tighter(T rule, T limit) {
  return rule > 0 ? std::min(rule, limit) : limit;
}

/// One identify(): its runs, the evaluations they spent, whether a wall-clock limit stopped one.
struct Pass {
  Identification id;
  long long spent = 0;
  bool timed_out = false;
};
Pass run_pass(const Model& model, const std::vector<const Signals*>& data, const Bounds& bounds,
              const OptimizerSpec& spec, const IdentificationSettings& settings) {
  Pass p{identify(model, data, bounds, make_optimizer_factory(spec), settings)};
  for (const RunResult& r : p.id.runs) {
    p.spent += r.evaluations;
    p.timed_out = p.timed_out || r.stop_reason == "wall_time";
  }
  return p;
}

/// Puts the second opinion's pass by `optimizer` in the report (its evaluations count in the fit's); whether its
/// wall-clock limit fired.
bool record_second_opinion(const Pass& opinion, const OptimizerSpec& optimizer, AutoBudgetReport& report) {
  report.second_opinion_evaluations = opinion.spent;
  report.evaluations += opinion.spent;
  report.second_opinion_optimizer = optimizer;
  report.second_opinion_best = best_of(opinion.id);
  return opinion.timed_out;
}

/// The progress line of round k: where the chains stand and what is spent.
std::string round_line(int k, int iterations, double best, const Convergence& verdict, const AutoBudgetReport& report) {
  return fmt::format("automatic budget: round {} ({} iterations): best {:.6g}, median run {} above it; {} of {} evaluations",
                     k, iterations, best, verdict.figure(verdict.median_above_best_rel, verdict.median_above_best),
                     report.evaluations, report.cap);
}

}  // namespace

void append_round(Identification& chains, const Identification& round) {
  if (chains.runs.empty()) {
    chains = round;
    return;
  }
  if (chains.runs.size() != round.runs.size())
    throw std::logic_error(fmt::format("append_round: {} chains, {} runs", chains.runs.size(), round.runs.size()));
  chains.wall_time_s += round.wall_time_s;
  chains.candidate_samples += round.candidate_samples;
  for (std::size_t r = 0; r < round.runs.size(); ++r) append_run(chains.runs[r], round.runs[r]);
}

Identification identify_until_converged(const Model& model, const std::vector<const Signals*>& data,
                                        const Bounds& bounds, const AutoBudget& budget,
                                        const IdentificationSettings& settings, AutoBudgetReport& report,
                                        const BudgetProgress& progress) {
  const int runs = settings.runs;
  if (runs < 2)
    throw InputError(fmt::format("the automatic budget needs at least 2 runs (one run cannot show that runs agree), "
                                 "got {}",
                                 runs));
  const int free = free_parameters(bounds);
  // Round 0's population as evaluated (cmaes's 0 is its default λ₀), for the cap and the report.
  const int population =
      budget.optimizer.population > 0 ? budget.optimizer.population : cmaes_default_population(free);
  const long long nominal = static_cast<long long>(runs) * population * budget.optimizer.iterations;
  report = {};
  const bool given_cap = budget.max_evaluations > 0;
  long long round0 = nominal;  // round 0's evaluations, once it ran (a local stage adds to R·P·I)
  const auto update_default_cap = [&] {
    if (!given_cap) report.cap = default_cap(round0, report.second_opinion_evaluations);
  };
  report.cap = given_cap ? budget.max_evaluations : default_cap(nominal, 0);
  report.last_restart_rel = std::numeric_limits<double>::infinity();
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  const auto pass = [&](const OptimizerSpec& spec, IdentificationSettings s) {
    if (budget.max_seconds > 0) s.budget.max_wall_time_s = tighter(s.budget.max_wall_time_s, budget.max_seconds - elapsed());
    return run_pass(model, data, bounds, spec, s);
  };

  Identification chains;
  for (int k = 0;; ++k) {
    OptimizerSpec spec = budget.optimizer;
    spec.iterations = round_iterations(budget.optimizer, k);
    IdentificationSettings s = settings;
    if (k > 0) s.task_key = hash_key({settings.task_key, static_cast<std::uint64_t>(k)});
    if (k == 0 && nominal > report.cap)  // a starved cap cuts round 0's runs to their share of it
      s.budget.max_evaluations = tighter(s.budget.max_evaluations, std::max<long long>(1, report.cap / runs));
    const Pass round = pass(spec, s);
    bool timed_out = round.timed_out;
    report.evaluations += round.spent;
    report.iterations.push_back(spec.iterations);
    if (k == 0) {
      round0 = std::max(nominal, round.spent);
      update_default_cap();
    }
    const double before = best_of(chains), restart = best_of(round.id);
    append_round(chains, round.id);
    const bool confirmed = k > 0 && restart_confirms(before, restart);
    const double best = best_of(chains);
    if (k > 0 && std::isfinite(before))  // relative to the chains' best after the round, min(before, restart)
      report.last_restart_rel = std::isfinite(restart) ? relative_to(restart - before, best)
                                                       : std::numeric_limits<double>::quiet_NaN();
    const Convergence verdict = assess_convergence(chains);
    const bool agreed = confirmed && verdict.converged;
    if (progress) progress(round_line(k, spec.iterations, best, verdict, report));
    if (agreed && !report.second_opinion_optimizer) {
      const OptimizerSpec other = second_opinion(model, budget.optimizer);
      IdentificationSettings o = settings;
      o.task_key = hash_key({settings.task_key, kSecondOpinionKey});
      o.runs = second_opinion_runs(model, settings.runs);
      timed_out = record_second_opinion(pass(other, o), other, report) || timed_out;
      update_default_cap();
      if (progress)
        progress(fmt::format("automatic budget: second opinion ({}, {} runs): best {:.6g}",
                             report.second_opinion_label(), o.runs, report.second_opinion_best));
    }
    if (report.second_opinion_optimizer) compare_second_opinion(report, best);
    if (agreed && !report.second_opinion_lower) report.stop = "converged";
    else if (timed_out || (budget.max_seconds > 0 && elapsed() >= budget.max_seconds)) report.stop = "time cap";
    else if (round.spent == 0 || report.evaluations + 2 * round.spent > report.cap ||
             budget.optimizer.iterations > (std::numeric_limits<int>::max() >> (k + 1)))
      report.stop = "cap";
    if (!report.stop.empty()) return chains;
  }
}

}  // namespace dampbench
