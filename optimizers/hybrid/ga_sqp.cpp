#include "optimizers/hybrid/ga_sqp.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>

#include <fmt/format.h>
#include <nlopt.h>

#include "engine/common/error.hpp"

namespace dampbench {

void GaSqpSettings::validate() const {
  validate_shared("ga-sqp");
  if (!(constraint > 0)) throw InputError(fmt::format("ga-sqp: constraint must be a number > 0 or off, got {}", constraint));
  check_ranges("ga-sqp", ga_sqp_setting_table(), *this);
}

const SettingTable<GaSqpSettings>& ga_sqp_setting_table() {
  static const SettingTable<GaSqpSettings> table{
      {"sqp_iterations", &GaSqpSettings::sqp_iterations, whole_at_least(1), "SLSQP function calls at most"},
      {"fd_step", &GaSqpSettings::fd_step, kFdStep, "forward-difference step, as a fraction of each parameter's range"},
      {"xtol", &GaSqpSettings::xtol, kNonNegative, "stop when the step in the unit box is below xtol, relative"},
      {"ftol", &GaSqpSettings::ftol, kNonNegative, "stop when the metric changes by less than ftol, relative"},
  };
  return table;
}

namespace {

std::string status_name(nlopt_result r) {
  switch (r) {
    case NLOPT_SUCCESS: return "success";
    case NLOPT_STOPVAL_REACHED: return "stopval";
    case NLOPT_FTOL_REACHED: return "ftol";
    case NLOPT_XTOL_REACHED: return "xtol";
    case NLOPT_MAXEVAL_REACHED: return "maxeval";
    case NLOPT_MAXTIME_REACHED: return "maxtime";
    case NLOPT_FAILURE: return "failure";
    case NLOPT_INVALID_ARGS: return "invalid_args";
    case NLOPT_OUT_OF_MEMORY: return "out_of_memory";
    case NLOPT_ROUNDOFF_LIMITED: return "roundoff";
    case NLOPT_FORCED_STOP: return "forced_stop";
    default: return fmt::format("nlopt_{}", static_cast<int>(r));
  }
}

/// One SLSQP solve: the callbacks' shared state. Evaluations at one position are cached, so the objective
/// and the constraint (NLopt asks both at every point) cost one evaluation.
struct SqpContext {
  SqpContext(const LocalProblem& p, const UnitBox& b, double step, double pen, double limit)
      : problem(p), box(b), h(step), penalty(pen), constraint(limit) {}

  const LocalProblem& problem;
  const UnitBox& box;
  double h;           ///< unit-cube difference step
  double penalty;     ///< stands in for a non-finite value
  double constraint;  ///< eq. 11 threshold
  BestSeen best;
  long long evaluations = 0;
  int calls = 0;
  std::exception_ptr error;
  nlopt_opt opt = nullptr;

  // cache of the last position
  std::vector<double> y;
  double f = 0;
  std::vector<double> grad;
  bool has_value = false, has_grad = false;

  CandidateBatch batch;
  std::vector<double> values, x;

  /// The metric at y (and its forward-difference gradient when asked), as one batch.
  void evaluate_at(const double* yp, bool want_grad) {
    const int m = box.free_dim();
    const bool same = has_value && std::equal(yp, yp + m, y.begin());
    if (same && (!want_grad || has_grad)) return;
    if (!same) {
      y.assign(yp, yp + m);
      has_value = has_grad = false;
    }
    const bool need_base = !has_value;
    const int rows = (need_base ? 1 : 0) + (want_grad ? m : 0);
    batch.resize(box.dim(), rows);
    values.assign(rows, 0.0);
    x.resize(box.dim());
    std::vector<double> yk = y;
    std::vector<double> steps(m);
    int row = 0;
    if (need_base) {
      box.to_params(yk, x);
      batch.set_candidate(row++, x);
    }
    if (want_grad) {
      for (int i = 0; i < m; ++i) {
        steps[i] = y[i] + h <= 1.0 ? h : -h;
        yk[i] = y[i] + steps[i];
        box.to_params(yk, x);
        batch.set_candidate(row++, x);
        yk[i] = y[i];
      }
    }
    problem.evaluate(batch, values);
    evaluations += rows;
    for (int r = 0; r < rows; ++r) best.offer(values[r], batch.candidate(r));
    row = 0;
    if (need_base) {
      f = values[row++];
      has_value = true;
    }
    if (want_grad) {
      grad.assign(m, 0.0);
      for (int i = 0; i < m; ++i, ++row)
        if (std::isfinite(values[row]) && std::isfinite(f)) grad[i] = (values[row] - f) / steps[i];
      has_grad = true;
    }
  }

  [[nodiscard]] double value() const { return std::isfinite(f) ? f : penalty; }
};

/// Evaluates the context at y (with its gradient when NLopt asks for one) and returns value(c); an exception
/// stops NLopt, is kept for rethrowing after it, and answers the penalty.
template <class Value>
double sqp_callback(unsigned n, const double* y, double* grad, void* data, Value value) {
  auto& c = *static_cast<SqpContext*>(data);
  try {
    c.evaluate_at(y, grad != nullptr);
  } catch (...) {
    c.error = std::current_exception();
    nlopt_force_stop(c.opt);
    if (grad) std::fill(grad, grad + n, 0.0);
    return c.penalty;
  }
  if (grad) std::copy(c.grad.begin(), c.grad.end(), grad);
  return value(c);
}

double sqp_objective(unsigned n, const double* y, double* grad, void* data) {
  ++static_cast<SqpContext*>(data)->calls;
  return sqp_callback(n, y, grad, data, [](const SqpContext& c) { return c.value(); });
}

double sqp_constraint(unsigned n, const double* y, double* grad, void* data) {
  return sqp_callback(n, y, grad, data, [](const SqpContext& c) { return c.value() - c.constraint; });
}

}  // namespace

bool GaSqp::at_local_optimum() const {
  const std::string& s = report_.status;
  return report_.ran && (s == "success" || s == "ftol" || s == "xtol");
}

GaSqp::GaSqp(const GaSqpSettings& settings, const Bounds& bounds, std::uint64_t run_key)
    : GaHybrid(validated(settings), bounds, run_key), settings_(settings) {}

void GaSqp::refine(const LocalProblem& problem) {
  report_ = {};
  report_.start_value = global().best_value();
  const UnitBox box(bounds_);
  BestSeen none;
  if (!std::isfinite(global().best_value()) || box.free_dim() == 0) {
    report_.status = box.free_dim() == 0 ? "no free parameters" : "the population phase found no finite value";
    finish_refine(none);
    report_.end_value = best_value();
    report_.feasible = best_value() <= settings_.constraint;
    return;
  }
  const int m = box.free_dim();
  SqpContext c(problem, box, settings_.fd_step, 1e6 * (1 + std::abs(global().best_value())), settings_.constraint);
  const std::unique_ptr<nlopt_opt_s, void (*)(nlopt_opt)> opt(nlopt_create(NLOPT_LD_SLSQP, static_cast<unsigned>(m)),
                                                             nlopt_destroy);
  c.opt = opt.get();
  nlopt_set_lower_bounds1(c.opt, 0.0);
  nlopt_set_upper_bounds1(c.opt, 1.0);
  nlopt_set_min_objective(c.opt, sqp_objective, &c);
  if (std::isfinite(settings_.constraint)) nlopt_add_inequality_constraint(c.opt, sqp_constraint, &c, 0.0);
  nlopt_set_maxeval(c.opt, settings_.sqp_iterations);
  nlopt_set_xtol_rel(c.opt, settings_.xtol);
  nlopt_set_xtol_abs1(c.opt, settings_.xtol);
  nlopt_set_ftol_rel(c.opt, settings_.ftol);

  std::vector<double> y = box.to_unit(global().best_position());
  double f_end = 0;
  const nlopt_result result = nlopt_optimize(c.opt, y.data(), &f_end);
  if (c.error) std::rethrow_exception(c.error);

  report_.ran = true;
  report_.status = status_name(result);
  report_.calls = c.calls;
  report_.evaluations = c.evaluations;
  finish_refine(c.best);
  report_.end_value = best_value();
  report_.feasible = best_value() <= settings_.constraint;
}

}  // namespace dampbench
