#include "optimizers/hybrid/ga_lm.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {

void GaLmSettings::validate() const {
  GeneticSettings::validate("ga-lm");
  validate_global();
  if (!(pc >= 0 && pc <= 1)) throw InputError(fmt::format("ga-lm: pc must be in [0, 1], got {}", pc));
  if (pm && !(*pm >= 0 && *pm <= 1)) throw InputError(fmt::format("ga-lm: pm must be in [0, 1], got {}", *pm));
  if (lm_iterations < 1) throw InputError(fmt::format("ga-lm: lm_iterations must be at least 1, got {}", lm_iterations));
  if (!(fd_step > 0 && fd_step <= 0.1)) throw InputError(fmt::format("ga-lm: fd_step must be in (0, 0.1], got {}", fd_step));
  if (!(ftol >= 0) || !std::isfinite(ftol)) throw InputError(fmt::format("ga-lm: ftol must be a finite number >= 0, got {}", ftol));
  if (!(xtol >= 0) || !std::isfinite(xtol)) throw InputError(fmt::format("ga-lm: xtol must be a finite number >= 0, got {}", xtol));
  if (!(gtol >= 0) || !std::isfinite(gtol)) throw InputError(fmt::format("ga-lm: gtol must be a finite number >= 0, got {}", gtol));
  if (!(lambda0 > 0) || !std::isfinite(lambda0))
    throw InputError(fmt::format("ga-lm: lambda0 must be a finite number > 0, got {}", lambda0));
  if (geodesic != 0 && geodesic != 1) throw InputError(fmt::format("ga-lm: geodesic must be 0 or 1, got {}", geodesic));
  if (!(geodesic_ratio > 0) || !std::isfinite(geodesic_ratio))
    throw InputError(fmt::format("ga-lm: geodesic_ratio must be a finite number > 0, got {}", geodesic_ratio));
}

namespace {

constexpr int kMaxRejectedSteps = 20;

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

  // ‖r(y)‖² (+inf when any residual is not finite), r written to `r`.
  std::size_t n = 0;
  auto cost_at = [&](const Eigen::VectorXd& y, Eigen::VectorXd& r) {
    const std::vector<double> res = problem.residuals(box.to_params(std::span<const double>(y.data(), m)));
    ++report_.residual_evaluations;
    if (n == 0) n = res.size();
    if (res.size() != n || n == 0) return std::numeric_limits<double>::infinity();
    r = Eigen::Map<const Eigen::VectorXd>(res.data(), static_cast<Eigen::Index>(n));
    const double s = r.squaredNorm();
    return std::isfinite(s) ? s : std::numeric_limits<double>::infinity();
  };

  const std::vector<double> start = box.to_unit(global().best_position());
  Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(start.data(), m);
  Eigen::VectorXd r;
  double S = cost_at(y, r);
  report_.start_cost = S;
  if (!std::isfinite(S)) {
    report_.status = "the population phase's best has non-finite residuals";
    report_.end_cost = S;
    finish_refine(seen);
    return;
  }
  report_.ran = true;
  report_.status = "iterations";

  std::vector<double> costs;  // ‖r‖² where each Jacobian was taken
  Eigen::MatrixXd J(static_cast<Eigen::Index>(n), m);
  Eigen::VectorXd r_step, r_new, y_new;
  double lambda = -1, nu = 2;
  int rejected = 0;
  bool stop = false;
  for (int it = 0; it < settings_.lm_iterations && !stop; ++it) {
    if (S <= 1e-300) {
      report_.status = "zero residual";
      break;
    }
    // Jacobian by forward differences: one residual vector per free parameter, all in one batch (lane
    // blocks, Model::simulate_block); the same values as one call each.
    std::vector<std::vector<double>> points;
    std::vector<double> steps;
    for (int i = 0; i < m; ++i) {
      const double s = y[i] + settings_.fd_step <= 1.0 ? settings_.fd_step : -settings_.fd_step;
      Eigen::VectorXd yk = y;
      yk[i] += s;
      points.push_back(box.to_params(std::span<const double>(yk.data(), m)));
      steps.push_back(s);
    }
    const std::vector<std::vector<double>> columns = problem.residuals_batch(points);
    report_.residual_evaluations += m;
    for (int i = 0; i < m; ++i) {
      const auto& res = columns[static_cast<std::size_t>(i)];
      const Eigen::Map<const Eigen::VectorXd> r_i(res.data(), static_cast<Eigen::Index>(res.size()));
      if (res.size() == n && std::isfinite(r_i.squaredNorm())) J.col(i) = (r_i - r) / steps[i];  // as cost_at accepts
      else J.col(i).setZero();
    }
    costs.push_back(S);
    ++report_.iterations;
    const Eigen::VectorXd g = J.transpose() * r;
    const Eigen::MatrixXd A = J.transpose() * J;

    // Free set: a parameter on a bound whose descent direction leaves the box is held.
    std::vector<int> free;
    double g_max = 0;
    for (int i = 0; i < m; ++i) {
      if ((y[i] <= 0 && g[i] > 0) || (y[i] >= 1 && g[i] < 0)) continue;
      free.push_back(i);
      g_max = std::max(g_max, std::abs(g[i]));
    }
    const double diag_max = A.diagonal().maxCoeff();
    if (free.empty() || g_max <= settings_.gtol || !(diag_max > 0)) {
      report_.status = "gradient";
      break;
    }
    if (lambda < 0) lambda = settings_.lambda0;
    const double diag_floor = 1e-12 * diag_max;
    const auto k = static_cast<Eigen::Index>(free.size());
    Eigen::MatrixXd Af(k, k);
    Eigen::VectorXd gf(k);
    for (Eigen::Index a = 0; a < k; ++a) {
      gf[a] = g[free[a]];
      for (Eigen::Index b = 0; b < k; ++b) Af(a, b) = A(free[a], free[b]);
    }

    // A refused step raises the damping; true when too many steps in a row were refused.
    const auto reject_step = [&] {
      lambda *= nu;
      nu *= 2;
      return ++rejected >= kMaxRejectedSteps || !std::isfinite(lambda);
    };
    for (;;) {  // until a step is accepted or a stopping rule holds
      Eigen::MatrixXd M = Af;
      for (Eigen::Index a = 0; a < k; ++a) M(a, a) += lambda * std::max(Af(a, a), diag_floor);
      const Eigen::LDLT<Eigen::MatrixXd> solver = M.ldlt();
      const Eigen::VectorXd vf = solver.solve(-gf);
      Eigen::VectorXd delta = Eigen::VectorXd::Zero(m);
      for (Eigen::Index a = 0; a < k; ++a) delta[free[a]] = vf[a];
      bool curvature_ok = true;
      if (settings_.geodesic) {
        // Geodesic acceleration (Transtrum & Sethna 2012): the second directional derivative of r along the
        // velocity v = delta by a finite difference, r_vv ≈ (2/h)((r(y + h·v) − r)/h − J·v), h = 0.1, gives
        // the acceleration a = −M⁻¹Jᵀr_vv; the step is v + a/2, refused when 2‖a‖/‖v‖ > geodesic_ratio.
        constexpr double h = 0.1;
        const Eigen::VectorXd probe = y + h * delta;
        if (probe.minCoeff() >= 0 && probe.maxCoeff() <= 1 && std::isfinite(cost_at(probe, r_step))) {
          const Eigen::VectorXd rvv = (2 / h) * ((r_step - r) / h - J * delta);
          const Eigen::VectorXd gvv = J.transpose() * rvv;
          Eigen::VectorXd gvvf(k);
          for (Eigen::Index a = 0; a < k; ++a) gvvf[a] = gvv[free[a]];
          const Eigen::VectorXd af = solver.solve(-gvvf);
          if (af.allFinite() && 2 * af.norm() <= settings_.geodesic_ratio * vf.norm()) {
            for (Eigen::Index a = 0; a < k; ++a) delta[free[a]] += 0.5 * af[a];
          } else {
            curvature_ok = false;
          }
        }
      }
      if (!curvature_ok) {
        if (reject_step()) {
          report_.status = "no progress";
          stop = true;
          break;
        }
        continue;
      }
      y_new = (y + delta).cwiseMax(0.0).cwiseMin(1.0);
      const Eigen::VectorXd d = y_new - y;
      if (!d.allFinite() || d.norm() <= settings_.xtol * (y.norm() + settings_.xtol)) {
        report_.status = "xtol";
        stop = true;
        break;
      }
      const double S_new = cost_at(y_new, r_new);
      if (S_new < S) {
        const double predicted = -(2 * d.dot(g) + d.dot(A * d));
        const double rho = predicted > 0 ? (S - S_new) / predicted : 1.0;
        lambda *= std::max(1.0 / 3.0, 1 - std::pow(2 * rho - 1, 3));
        nu = 2;
        rejected = 0;
        const double decrease = (S - S_new) / S;
        y = y_new;
        r = r_new;
        S = S_new;
        if (decrease <= settings_.ftol) {
          report_.status = "ftol";
          stop = true;
        }
        break;
      }
      if (reject_step()) {
        report_.status = "no progress";
        stop = true;
        break;
      }
    }
  }
  report_.end_cost = S;
  if (!costs.empty()) {
    const std::size_t last_fifth = std::max<std::size_t>(1, (costs.size() + 4) / 5);
    report_.late_decrease = 1 - std::sqrt(S / costs[costs.size() - last_fifth]);
  }

  // The end point in the run metric's terms.
  const std::vector<double> x = box.to_params(std::span<const double>(y.data(), m));
  CandidateBatch one(box.dim(), 1);
  one.set_candidate(0, x);
  double metric = 0;
  problem.evaluate(one, std::span<double>(&metric, 1));
  report_.end_metric = metric;
  seen.offer(metric, x);
  finish_refine(seen);
}

}  // namespace dampbench
