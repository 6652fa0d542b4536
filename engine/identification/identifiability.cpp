#include "engine/identification/identifiability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "engine/identification/identification.hpp"

namespace dampbench {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMaxRelativeError = 1.0, kMaxCorrelation = 0.99, kBoundTolerance = 1e-6, kSingular = 1e-10;
}  // namespace

bool Identifiability::all_identifiable() const {
  return std::all_of(flags.begin(), flags.end(), [](const auto& f) { return f.empty(); });
}

namespace {
constexpr std::string_view kNotIdentifiable = "not identifiable", kCorrelated = "correlated", kAtBound = "at bound";
bool has_flag(const std::vector<std::vector<std::string>>& flags, int j, std::string_view start) {
  if (j < 0 || j >= static_cast<int>(flags.size())) return false;
  const auto& f = flags[static_cast<std::size_t>(j)];
  return std::any_of(f.begin(), f.end(), [&](const std::string& x) { return x.starts_with(start); });
}
}  // namespace

bool Identifiability::determined(int j) const {
  return !has_flag(flags, j, kNotIdentifiable) && !has_flag(flags, j, kCorrelated);
}

bool Identifiability::at_bound(int j) const { return has_flag(flags, j, kAtBound); }

std::string Identifiability::summary(const Model& model) const {
  std::string out;
  for (std::size_t j = 0; j < flags.size(); ++j)
    for (const std::string& f : flags[j]) out += fmt::format("{}{}: {}", out.empty() ? "" : "; ", model.parameters()[j].name, f);
  return out.empty() ? "ok" : out;
}

namespace {

/// The Jacobian of the scaled residuals at the best parameters by central differences, with a step relative to the
/// value, or to the box where the value is 0; a step that would leave the box is taken one-sided. The best point
/// and the 2p steps are simulated in one batch. `ssr` is the best point's sum of squared residuals.
Eigen::MatrixXd residual_jacobian(const Model& model, std::span<const Signals* const> data, const Bounds& bounds,
                                  std::span<const double> best_params, double& ssr) {
  const int p = model.dim();
  std::vector<std::vector<double>> points{std::vector<double>(best_params.begin(), best_params.end())};
  std::vector<double> up(p), down(p);
  for (int j = 0; j < p; ++j) {
    const double width = bounds.upper[j] - bounds.lower[j];
    const double h = 1e-6 * std::max(std::abs(best_params[j]), 1e-3 * width);
    up[j] = std::min(best_params[j] + h, bounds.upper[j]);
    down[j] = std::max(best_params[j] - h, bounds.lower[j]);
    for (double v : {up[j], down[j]}) {
      points.push_back(points.front());
      points.back()[static_cast<std::size_t>(j)] = v;
    }
  }
  const std::vector<std::vector<double>> residuals = scaled_residuals(model, data, points);
  const std::vector<double>& r0 = residuals.front();
  const auto n = static_cast<Eigen::Index>(r0.size());
  Eigen::MatrixXd J(n, p);
  for (int j = 0; j < p; ++j) {
    const std::vector<double>&ru = residuals[static_cast<std::size_t>(1 + 2 * j)], &rd = residuals[static_cast<std::size_t>(2 + 2 * j)];
    for (Eigen::Index k = 0; k < n; ++k) J(k, j) = up[j] > down[j] ? (ru[k] - rd[k]) / (up[j] - down[j]) : 0.0;
  }
  ssr = 0;
  for (double v : r0) ssr += v * v;
  return J;
}

/// The flags of every estimated parameter (identifiability.hpp): not identifiable, correlated, at bound.
void flag_parameters(const Model& model, const Bounds& bounds, std::span<const double> best_params,
                     const std::vector<bool>& fixed, Identifiability& out) {
  const int p = model.dim();
  const auto params = model.parameters();
  for (int j = 0; j < p; ++j) {
    if (fixed[j]) continue;
    if (!(out.relative_error[j] <= kMaxRelativeError)) out.flags[j].emplace_back(kNotIdentifiable);
    for (int i = 0; i < p; ++i)
      if (i != j && std::abs(out.correlation[i][j]) > kMaxCorrelation)
        out.flags[j].push_back(fmt::format("{} with {} ({:+.3f})", kCorrelated, params[i].name, out.correlation[i][j]));
    const double width = bounds.upper[j] - bounds.lower[j];
    if (width > 0 && (best_params[j] - bounds.lower[j] <= kBoundTolerance * width ||
                      bounds.upper[j] - best_params[j] <= kBoundTolerance * width))
      out.flags[j].emplace_back(kAtBound);
  }
}

}  // namespace

Identifiability assess_identifiability(const Model& model, std::span<const Signals* const> data, const Bounds& bounds,
                                       std::span<const double> best_params) {
  const int p = model.dim();
  double ssr = 0;
  const Eigen::MatrixXd J = residual_jacobian(model, data, bounds, best_params, ssr);
  const Eigen::Index n = J.rows();
  const double s2 = ssr / std::max<Eigen::Index>(n - p, 1);

  // cov = s²·V Σ⁻² Vᵀ over the resolved directions; a direction with a (near) zero singular value is
  // unresolved, and every parameter with weight in it gets an infinite standard error.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  const Eigen::MatrixXd& V = svd.matrixV();
  const double largest = sv.size() ? sv[0] : 0.0;
  // Unresolved directions still carry their correlation (`dir`): the parameters move together along V's column.
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(p, p), dir = Eigen::MatrixXd::Zero(p, p);
  std::vector<bool> unresolved(p, false);
  for (Eigen::Index i = 0; i < sv.size(); ++i) {
    if (!(sv[i] > kSingular * largest)) {
      for (int j = 0; j < p; ++j) unresolved[j] = unresolved[j] || std::abs(V(j, i)) > 1e-3;
      dir += V.col(i) * V.col(i).transpose();
      continue;
    }
    cov += (s2 / (sv[i] * sv[i])) * V.col(i) * V.col(i).transpose();
  }

  Identifiability out;
  out.samples = static_cast<int>(n);
  out.std_error.resize(p);
  out.relative_error.resize(p);
  out.correlation.assign(p, std::vector<double>(p, 0.0));
  out.flags.resize(p);
  std::vector<bool> fixed(p);
  for (int j = 0; j < p; ++j) fixed[j] = !(bounds.upper[j] > bounds.lower[j]);  // held by its bounds: not estimated
  for (int j = 0; j < p; ++j) {
    if (fixed[j]) unresolved[j] = false;
    out.std_error[j] = fixed[j] ? 0.0 : unresolved[j] ? kInf : std::sqrt(std::max(cov(j, j), 0.0));
    const double mag = std::abs(best_params[j]);
    out.relative_error[j] = mag > 0 ? out.std_error[j] / mag : (out.std_error[j] > 0 ? kInf : 0.0);
  }
  for (int i = 0; i < p; ++i)
    for (int j = 0; j < p; ++j) {
      double c;
      if (i == j) c = 1.0;
      else if (fixed[i] || fixed[j]) c = 0.0;
      else if (unresolved[i] && unresolved[j] && dir(i, i) > 0 && dir(j, j) > 0) c = dir(i, j) / std::sqrt(dir(i, i) * dir(j, j));
      else if (out.std_error[i] > 0 && out.std_error[j] > 0 && std::isfinite(out.std_error[i] * out.std_error[j]))
        c = cov(i, j) / (out.std_error[i] * out.std_error[j]);
      else c = 0.0;
      out.correlation[i][j] = c;
    }
  flag_parameters(model, bounds, best_params, fixed, out);
  return out;
}

}  // namespace dampbench
