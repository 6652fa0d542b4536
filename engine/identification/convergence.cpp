#include "engine/identification/convergence.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dampbench {

std::vector<TracePoint> improvement_points(const RunResult& run) {
  std::vector<TracePoint> t;
  for (std::size_t i = 0; i < run.trace.size(); ++i)
    if (i == 0 || run.trace[i] < run.trace[i - 1] || i + 1 == run.trace.size())
      t.push_back({run.trace_evaluations[i], run.trace[i]});
  // The end: a local stage's evaluations, or, after a float32 search (`--precision mixed`), the float64 value of the
  // best where it is lower than the search's own; the history stays non-increasing either way.
  if (!t.empty() && run.evaluations != t.back().evaluations)
    t.push_back({run.evaluations, std::min(run.best_value, t.back().value)});
  else if (!t.empty())
    t.back().value = std::min(run.best_value, t.back().value);
  return t;
}

std::string Convergence::verdict() const {
  if (converged) return "converged";
  if (all_failed) return "every run failed";
  if (single_run) return stalled ? "one run" : (no_history ? "one run, no history" : "one run, still improving");
  if (no_history) return runs_agree ? "no history" : "runs disagree, no history";
  if (!runs_agree && !stalled) return "runs disagree, still improving";
  if (runs_agree && stalled) return "not confirmed by a restart";
  return runs_agree ? "still improving" : "runs disagree";
}

std::string Convergence::figure(double relative, double absolute) const {
  return relative_figures ? fmt::format("{:.3g} %", 100 * relative) : fmt::format("{:.3g}", absolute);
}

std::string Convergence::spread_text(const ConvergenceRule& rule) const {
  const std::string units =
      relative_figures ? "" : fmt::format("the best is {:.3g}, within {:.3g} of 0, so the differences are in the "
                                          "metric's units: ", best_value, rule.abs_tol);
  // the trace is the search's (float32 lanes under --precision mixed) and the best is re-evaluated in double, so a
  // run that did not improve can show a gain of -1e-8: none
  return fmt::format("{}the median run ends {} above the best, the worst {}; the best run improved {} over its last "
                     "{:.0f} % of evaluations",
                     units, figure(median_above_best_rel, median_above_best), figure(worst_above_best_rel, worst_above_best),
                     figure(std::max(0.0, late_gain_rel), std::max(0.0, late_gain)), 100 * rule.late_fraction);
}

namespace {

/// The best-so-far value of a history after `evaluations` (+inf before its first point).
double value_at(const std::vector<TracePoint>& trace, double evaluations) {
  double v = std::numeric_limits<double>::infinity();
  for (const TracePoint& p : trace) {
    if (static_cast<double>(p.evaluations) > evaluations) break;
    v = p.value;
  }
  return v;
}

}  // namespace

Convergence assess_convergence(std::span<const RunHistory> runs, const ConvergenceRule& rule, bool unconfirmed) {
  Convergence c;
  std::vector<double> values;
  const RunHistory* best = nullptr;
  for (const RunHistory& r : runs) {
    values.push_back(std::isnan(r.best_value) ? std::numeric_limits<double>::infinity() : r.best_value);
    if (!best || values.back() < best->best_value) best = &r;
  }
  if (!best || !std::isfinite(best->best_value)) {
    c.median_above_best_rel = c.worst_above_best_rel = std::numeric_limits<double>::infinity();
    c.all_failed = true;
    return c;
  }
  std::sort(values.begin(), values.end());
  const double b = values.front(), scale = std::abs(b);
  // The median of an even count is the upper middle value: half of the runs must be within the tolerance.
  const double median = values[values.size() / 2], worst = values.back();
  const auto rel = [&](double above) { return scale > 0 ? above / scale : (above > 0 ? HUGE_VAL : 0.0); };
  c.best_value = b;
  c.relative_figures = scale > rule.abs_tol;
  c.median_above_best_rel = rel(median - b);
  c.worst_above_best_rel = rel(worst - b);
  c.median_above_best = median - b;
  c.worst_above_best = worst - b;
  c.single_run = runs.size() == 1;
  c.runs_agree = !c.single_run && median - b <= rule.agree_rel * scale + rule.abs_tol;

  const double total = best->trace.empty() ? 0.0 : static_cast<double>(best->trace.back().evaluations);
  const double earlier = value_at(best->trace, total * (1 - rule.late_fraction));
  const double gain = earlier - best->best_value;
  c.late_gain_rel = rel(gain);
  c.late_gain = gain;
  c.no_history = best->trace.empty();
  c.best_at_local_optimum = best->at_local_optimum;
  c.stalled = !c.no_history && (best->at_local_optimum || gain <= rule.late_gain_rel * scale + rule.abs_tol);
  c.unconfirmed = unconfirmed;
  c.converged = c.runs_agree && c.stalled && !unconfirmed;
  return c;
}

Convergence assess_convergence(const Identification& id, const ConvergenceRule& rule, bool unconfirmed) {
  std::vector<RunHistory> runs;
  for (const RunResult& r : id.runs) runs.push_back({r.best_value, improvement_points(r), r.at_local_optimum});
  return assess_convergence(runs, rule, unconfirmed);
}

}  // namespace dampbench
