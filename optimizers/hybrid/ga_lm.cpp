#include "optimizers/hybrid/ga_lm.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {

void GaLmSettings::validate() const {
  validate_shared("ga-lm");
  check_ranges("ga-lm", ga_lm_setting_table(), *this);
}

const SettingTable<GaLmSettings>& ga_lm_setting_table() {
  static const SettingTable<GaLmSettings> table{
      {"lm_iterations", &GaLmSettings::lm_iterations, whole_at_least(1), "Levenberg–Marquardt Jacobians at most"},
      {"fd_step", &GaLmSettings::fd_step, kFdStep, "forward-difference step, as a fraction of each parameter's range"},
      {"ftol", &GaLmSettings::ftol, kNonNegative, "stop when an accepted step lowers the squared residual by less, relative"},
      {"xtol", &GaLmSettings::xtol, kNonNegative, "stop when the step in the unit box is below xtol·(‖y‖ + xtol)"},
      {"gtol", &GaLmSettings::gtol, kNonNegative, "stop when the projected gradient's largest entry is at most gtol"},
      {"lambda0", &GaLmSettings::lambda0, kPositive, "initial damping, relative to diag(JᵀJ)"},
      {"geodesic", &GaLmSettings::geodesic, {0, 1, false, false, true}, "1: geodesic acceleration, 0: plain LM"},
      {"geodesic_ratio", &GaLmSettings::geodesic_ratio, kPositive, "largest accepted 2‖a‖/‖v‖ of the acceleration"},
  };
  return table;
}

namespace {

constexpr int kMaxRejectedSteps = 20;

/// The bounded Levenberg–Marquardt of ga_lm.hpp in the unit box of the free parameters, from the point y:
/// `run` iterates (a Jacobian, the free set, damped steps until one is accepted or a stopping rule holds) and
/// leaves the end point in y, its cost in S and the reason it stopped in the report.
class BoundedLm {
 public:
  BoundedLm(const LocalProblem& problem, const UnitBox& box, const GaLmSettings& settings, LmReport& report)
      : problem_(problem), box_(box), settings_(settings), report_(report), m_(box.free_dim()) {}

  /// ‖r(y)‖² (+inf when any residual is not finite), r written to `r`.
  double cost_at(const Eigen::VectorXd& y, Eigen::VectorXd& r) {
    return cost_of(problem_.residuals(box_.to_params(std::span<const double>(y.data(), m_))), r);
  }

  /// cost_at of a trial point y; where the problem has idle lanes beside it (LocalProblem::residuals_ahead) and an
  /// iteration follows, the Jacobian at y comes in the same batch and take_jacobian uses it if y is accepted: a
  /// trial and the next Jacobian in one lane block instead of two, the same values.
  double trial_cost_at(const Eigen::VectorXd& y, Eigen::VectorXd& r) {
    ahead_.clear();
    if (report_.iterations >= settings_.lm_iterations) return cost_at(y, r);
    std::vector<std::vector<double>> points{box_.to_params(std::span<const double>(y.data(), m_))};
    jacobian_points(y, points, ahead_steps_);
    std::vector<std::vector<double>> res = problem_.residuals_ahead(points);
    if (res.size() != points.size()) return cost_at(y, r);
    ahead_.assign(std::make_move_iterator(res.begin() + 1), std::make_move_iterator(res.end()));
    return cost_of(res.front(), r);
  }

  /// ‖r‖² of residuals `res` (+inf when any is not finite or their count differs from the first's), r = res; counts
  /// one evaluation.
  double cost_of(const std::vector<double>& res, Eigen::VectorXd& r) {
    ++report_.residual_evaluations;
    if (n_ == 0) n_ = res.size();
    if (res.size() != n_ || n_ == 0) return std::numeric_limits<double>::infinity();
    r = Eigen::Map<const Eigen::VectorXd>(res.data(), static_cast<Eigen::Index>(n_));
    const double s = r.squaredNorm();
    return std::isfinite(s) ? s : std::numeric_limits<double>::infinity();
  }

  /// Starts at y (its cost finite: the caller checked it with cost_at into r) and iterates.
  void run(Eigen::VectorXd y, Eigen::VectorXd r, double S) {
    y_ = std::move(y), r_ = std::move(r), S_ = S;
    J_.resize(static_cast<Eigen::Index>(n_), m_);
    bool stop = false;
    for (int it = 0; it < settings_.lm_iterations && !stop; ++it) {
      if (S_ <= 1e-300) {
        report_.status = "zero residual";
        break;
      }
      take_jacobian();
      costs_.push_back(S_);
      ++report_.iterations;
      const Eigen::VectorXd g = J_.transpose() * r_;
      const Eigen::MatrixXd A = J_.transpose() * J_;
      if (!free_set(g, A)) {
        report_.status = "gradient";
        break;
      }
      if (lambda_ < 0) lambda_ = settings_.lambda0;
      stop = step(g, A);
    }
  }

  [[nodiscard]] const Eigen::VectorXd& y() const { return y_; }
  [[nodiscard]] double cost() const { return S_; }
  [[nodiscard]] const std::vector<double>& costs() const { return costs_; }  ///< ‖r‖² where each Jacobian was taken

 private:
  /// The forward-difference points around y, appended to `points`, and their steps.
  void jacobian_points(const Eigen::VectorXd& y, std::vector<std::vector<double>>& points, std::vector<double>& steps) const {
    steps.clear();
    for (int i = 0; i < m_; ++i) {
      const double s = y[i] + settings_.fd_step <= 1.0 ? settings_.fd_step : -settings_.fd_step;
      Eigen::VectorXd yk = y;
      yk[i] += s;
      points.push_back(box_.to_params(std::span<const double>(yk.data(), m_)));
      steps.push_back(s);
    }
  }

  /// Jacobian by forward differences: one residual vector per free parameter, all in one batch (lane blocks,
  /// Model::simulate_block), or the one computed beside the accepted trial (trial_cost_at); the same values as
  /// one call each.
  void take_jacobian() {
    std::vector<std::vector<double>> columns;
    std::vector<double> steps;
    if (ahead_ready_) {
      columns = std::move(ahead_), steps = ahead_steps_;
      problem_.count_evaluations(m_);
    } else {
      std::vector<std::vector<double>> points;
      jacobian_points(y_, points, steps);
      columns = problem_.residuals_batch(points);
    }
    ahead_.clear();
    ahead_ready_ = false;
    report_.residual_evaluations += m_;
    for (int i = 0; i < m_; ++i) {
      const auto& res = columns[static_cast<std::size_t>(i)];
      const Eigen::Map<const Eigen::VectorXd> r_i(res.data(), static_cast<Eigen::Index>(res.size()));
      if (res.size() == n_ && std::isfinite(r_i.squaredNorm())) J_.col(i) = (r_i - r_) / steps[i];  // as cost_at accepts
      else J_.col(i).setZero();
    }
  }

  /// Free set: a parameter on a bound whose descent direction leaves the box is held. Fills free_, Af_, gf_ and
  /// the diagonal floor; false when nothing can move (the gradient test, or no curvature).
  bool free_set(const Eigen::VectorXd& g, const Eigen::MatrixXd& A) {
    free_.clear();
    double g_max = 0;
    for (int i = 0; i < m_; ++i) {
      if ((y_[i] <= 0 && g[i] > 0) || (y_[i] >= 1 && g[i] < 0)) continue;
      free_.push_back(i);
      g_max = std::max(g_max, std::abs(g[i]));
    }
    const double diag_max = A.diagonal().maxCoeff();
    if (free_.empty() || g_max <= settings_.gtol || !(diag_max > 0)) return false;
    diag_floor_ = 1e-12 * diag_max;
    const auto k = static_cast<Eigen::Index>(free_.size());
    Af_.resize(k, k);
    gf_.resize(k);
    for (Eigen::Index a = 0; a < k; ++a) {
      gf_[a] = g[free_[a]];
      for (Eigen::Index b = 0; b < k; ++b) Af_(a, b) = A(free_[a], free_[b]);
    }
    return true;
  }

  /// A refused step raises the damping; true when too many steps in a row were refused.
  bool reject_step() {
    lambda_ *= nu_;
    nu_ *= 2;
    return ++rejected_ >= kMaxRejectedSteps || !std::isfinite(lambda_);
  }

  /// Geodesic acceleration (Transtrum & Sethna 2012): the second directional derivative of r along the
  /// velocity v = delta by a finite difference, r_vv ≈ (2/h)((r(y + h·v) − r)/h − J·v), h = 0.1, gives the
  /// acceleration a = −M⁻¹Jᵀr_vv; the step becomes v + a/2. False (the step refused) when 2‖a‖/‖v‖ >
  /// geodesic_ratio.
  bool accelerate(const Eigen::LDLT<Eigen::MatrixXd>& solver, const Eigen::VectorXd& vf, Eigen::VectorXd& delta) {
    constexpr double h = 0.1;
    const Eigen::VectorXd probe = y_ + h * delta;
    if (!(probe.minCoeff() >= 0 && probe.maxCoeff() <= 1 && std::isfinite(cost_at(probe, r_step_)))) return true;
    const Eigen::VectorXd rvv = (2 / h) * ((r_step_ - r_) / h - J_ * delta);
    const Eigen::VectorXd gvv = J_.transpose() * rvv;
    const auto k = static_cast<Eigen::Index>(free_.size());
    Eigen::VectorXd gvvf(k);
    for (Eigen::Index a = 0; a < k; ++a) gvvf[a] = gvv[free_[a]];
    const Eigen::VectorXd af = solver.solve(-gvvf);
    if (!(af.allFinite() && 2 * af.norm() <= settings_.geodesic_ratio * vf.norm())) return false;
    for (Eigen::Index a = 0; a < k; ++a) delta[free_[a]] += 0.5 * af[a];
    return true;
  }

  /// Damped steps on the free set until one is accepted (false) or a stopping rule holds (true, status set).
  bool step(const Eigen::VectorXd& g, const Eigen::MatrixXd& A) {
    const auto k = static_cast<Eigen::Index>(free_.size());
    for (;;) {
      Eigen::MatrixXd M = Af_;
      for (Eigen::Index a = 0; a < k; ++a) M(a, a) += lambda_ * std::max(Af_(a, a), diag_floor_);
      const Eigen::LDLT<Eigen::MatrixXd> solver = M.ldlt();
      const Eigen::VectorXd vf = solver.solve(-gf_);
      Eigen::VectorXd delta = Eigen::VectorXd::Zero(m_);
      for (Eigen::Index a = 0; a < k; ++a) delta[free_[a]] = vf[a];
      if (settings_.geodesic && !accelerate(solver, vf, delta)) {
        if (!reject_step()) continue;
        report_.status = "no progress";
        return true;
      }
      y_new_ = (y_ + delta).cwiseMax(0.0).cwiseMin(1.0);
      const Eigen::VectorXd d = y_new_ - y_;
      if (!d.allFinite() || d.norm() <= settings_.xtol * (y_.norm() + settings_.xtol)) {
        report_.status = "xtol";
        return true;
      }
      const double S_new = trial_cost_at(y_new_, r_new_);
      if (S_new < S_) return accept(d, g, A, S_new);
      if (reject_step()) {
        report_.status = "no progress";
        return true;
      }
    }
  }

  /// Takes the step to y_new_ (cost S_new < S_), updates the damping by the gain ratio; true on ftol.
  bool accept(const Eigen::VectorXd& d, const Eigen::VectorXd& g, const Eigen::MatrixXd& A, double S_new) {
    const double predicted = -(2 * d.dot(g) + d.dot(A * d));
    const double rho = predicted > 0 ? (S_ - S_new) / predicted : 1.0;
    lambda_ *= std::max(1.0 / 3.0, 1 - std::pow(2 * rho - 1, 3));
    nu_ = 2;
    rejected_ = 0;
    const double decrease = (S_ - S_new) / S_;
    y_ = y_new_;
    r_ = r_new_;
    S_ = S_new;
    ahead_ready_ = !ahead_.empty();
    if (!(decrease <= settings_.ftol)) return false;
    report_.status = "ftol";
    return true;
  }

  const LocalProblem& problem_;
  const UnitBox& box_;
  const GaLmSettings& settings_;
  LmReport& report_;
  const int m_;
  std::size_t n_ = 0;  // residuals per evaluation, from the first
  Eigen::VectorXd y_, r_, r_step_, r_new_, y_new_;
  double S_ = 0;
  Eigen::MatrixXd J_;
  std::vector<double> costs_;
  std::vector<int> free_;
  Eigen::MatrixXd Af_;
  Eigen::VectorXd gf_;
  double diag_floor_ = 0;
  double lambda_ = -1, nu_ = 2;
  int rejected_ = 0;
  std::vector<std::vector<double>> ahead_;  // residuals of the Jacobian's points around the last trial (or empty)
  std::vector<double> ahead_steps_;         // their steps
  bool ahead_ready_ = false;                // ahead_ is the Jacobian at y_ (its trial was accepted)
};

}  // namespace

bool GaLm::at_local_optimum() const {
  const std::string& s = report_.status;
  if (!report_.ran) return false;
  if (s == "iterations") return report_.late_decrease <= kStalledDecrease;  // false for NaN
  return s == "gradient" || s == "ftol" || s == "xtol" || s == "zero residual";
}

GaLm::GaLm(const GaLmSettings& settings, const Bounds& bounds, std::uint64_t run_key)
    : GaHybrid(validated(settings), bounds, run_key), settings_(settings) {}

void GaLm::refine(const LocalProblem& problem) {
  report_ = {};
  const UnitBox box(bounds_);
  const int m = box.free_dim();
  BestSeen seen;
  if (!std::isfinite(global().best_value()) || m == 0) {
    report_.status = m == 0 ? "no free parameters" : "the population phase found no finite value";
    finish_refine(seen);
    return;
  }
  BoundedLm lm(problem, box, settings_, report_);
  const std::vector<double> start = box.to_unit(global().best_position());
  Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(start.data(), m);
  Eigen::VectorXd r;
  const double S = lm.cost_at(y, r);
  report_.start_cost = S;
  if (!std::isfinite(S)) {
    report_.status = "the population phase's best has non-finite residuals";
    report_.end_cost = S;
    finish_refine(seen);
    return;
  }
  report_.ran = true;
  report_.status = "iterations";
  lm.run(std::move(y), std::move(r), S);
  report_.end_cost = lm.cost();
  const std::vector<double>& costs = lm.costs();
  if (!costs.empty()) {
    const std::size_t last_fifth = std::max<std::size_t>(1, (costs.size() + 4) / 5);
    report_.late_decrease = 1 - std::sqrt(lm.cost() / costs[costs.size() - last_fifth]);
  }

  // The end point in the run metric's terms.
  const std::vector<double> x = box.to_params(std::span<const double>(lm.y().data(), m));
  CandidateBatch one(box.dim(), 1);
  one.set_candidate(0, x);
  double metric = 0;
  problem.evaluate(one, std::span<double>(&metric, 1));
  report_.end_metric = metric;
  seen.offer(metric, x);
  finish_refine(seen);
}

}  // namespace dampbench
