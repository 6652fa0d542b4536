#include "optimizers/cmaes/strategy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "engine/common/random.hpp"
#include "optimizers/random_draws.hpp"

namespace dampbench {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A value as the ranking sees it: a failed candidate (NaN, ±inf) is +inf, behind every finite value.
double ranked(double v) { return std::isfinite(v) ? v : kInf; }

double median_of(std::vector<double>::const_iterator first, std::vector<double>::const_iterator last) {
  std::vector<double> v(first, last);
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

CmaStrategy::CmaStrategy(const Eigen::VectorXd& mean, double sigma, int lambda, const CmaTolerances& tolerances)
    : n_(static_cast<int>(mean.size())), lambda_(lambda), mu_(lambda / 2), tol_(tolerances), sigma0_(sigma),
      m_(mean), sigma_(sigma) {
  set_weights();
  ps_ = pc_ = Eigen::VectorXd::Zero(n_);
  D_ = Eigen::VectorXd::Ones(n_);
  C_ = B_ = inv_sqrt_C_ = Eigen::MatrixXd::Identity(n_, n_);
}

void CmaStrategy::set_weights() {
  const double n = n_;
  Eigen::VectorXd raw(lambda_);
  for (int i = 0; i < lambda_; ++i) raw[i] = std::log((lambda_ + 1) / 2.0) - std::log(i + 1.0);
  const double pos_sum = raw.head(mu_).sum(), pos_sq = raw.head(mu_).squaredNorm();
  const double neg_sum = raw.tail(lambda_ - mu_).sum(), neg_sq = raw.tail(lambda_ - mu_).squaredNorm();
  mueff_ = pos_sum * pos_sum / pos_sq;
  const double mueff_neg = neg_sq > 0 ? neg_sum * neg_sum / neg_sq : 0;
  c1_ = 2 / ((n + 1.3) * (n + 1.3) + mueff_);
  cmu_ = std::min(1 - c1_, 2 * (mueff_ - 2 + 1 / mueff_) / ((n + 2) * (n + 2) + mueff_));
  // With c_μ = 0 (λ ≤ 3) the first and last bounds are +inf and the middle one applies.
  const double alpha_neg = std::min({1 + c1_ / cmu_, 1 + 2 * mueff_neg / (mueff_ + 2), (1 - c1_ - cmu_) / (n * cmu_)});
  w_.resize(lambda_);
  for (int i = 0; i < lambda_; ++i) w_[i] = raw[i] >= 0 ? raw[i] / pos_sum : alpha_neg * raw[i] / std::abs(neg_sum);
  cs_ = (mueff_ + 2) / (n + mueff_ + 5);
  ds_ = 1 + 2 * std::max(0.0, std::sqrt((mueff_ - 1) / (n + 1)) - 1) + cs_;
  cc_ = (4 + mueff_ / n) / (n + 4 + 2 * mueff_ / n);
  chi_n_ = std::sqrt(n) * (1 - 1 / (4 * n) + 1 / (21 * n * n));
}

void CmaStrategy::sample(std::uint64_t generation_key, Eigen::MatrixXd& samples) {
  // Sample k's n normals are the first n of stream extend_key(generation_key, k), drawn for all λ in one vector
  // loop (random_draws.hpp): column k of Z.
  sample_keys_.resize(static_cast<std::size_t>(lambda_));
  member_keys(generation_key, sample_keys_);
  first_normals(sample_keys_, n_, normals_, uniforms_, key_scratch_);
  const Eigen::Map<const Eigen::MatrixXd> z(normals_.data(), n_, lambda_);
  samples.noalias() = (sigma_ * (B_ * D_.asDiagonal())) * z;
  samples.colwise() += m_;
}

std::vector<int> CmaStrategy::ranking(std::span<const double> values) const {
  const auto n = static_cast<std::size_t>(lambda_);
  std::vector<std::pair<double, int>> keyed(n);
  for (std::size_t i = 0; i < n; ++i) keyed[i] = {ranked(values[i]), static_cast<int>(i)};
  std::sort(keyed.begin(), keyed.end());  // ties in index order, as a stable sort of the values gives them
  std::vector<int> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = keyed[i].second;
  return order;
}

void CmaStrategy::update(const Eigen::MatrixXd& samples, std::span<const double> values) {
  const std::vector<int> order = ranking(values);
  Eigen::MatrixXd y(n_, lambda_);  // steps (x − m)/σ, best first
  for (int i = 0; i < lambda_; ++i) y.col(i) = (samples.col(order[static_cast<std::size_t>(i)]) - m_) / sigma_;
  const Eigen::VectorXd y_w = y.leftCols(mu_) * w_.head(mu_);
  adapt(y, y_w);
  ++generation_;
  // Lazily: after more than λ/(c_1 + c_μ)/n/10 evaluations, i.e. 1/(c_1 + c_μ)/n/10 generations.
  if (generation_ - decomposed_at_ > 1 / (c1_ + cmu_) / n_ / 10) decompose();
  record(values, order);
  stop_ = first_stop(values);
}

void CmaStrategy::adapt(const Eigen::MatrixXd& y, const Eigen::VectorXd& y_w) {
  m_ += sigma_ * y_w;
  ps_ = (1 - cs_) * ps_ + std::sqrt(cs_ * (2 - cs_) * mueff_) * (inv_sqrt_C_ * y_w);
  const double ps_norm = ps_.norm();
  const bool hs = ps_norm / std::sqrt(1 - std::pow(1 - cs_, 2.0 * (generation_ + 1))) <
                  (1.4 + 2.0 / (n_ + 1)) * chi_n_;
  pc_ = (1 - cc_) * pc_ + (hs ? std::sqrt(cc_ * (2 - cc_) * mueff_) : 0.0) * y_w;
  Eigen::VectorXd w = w_;  // w°: negative weights rescaled by n/‖C^−1/2 y‖²
  for (int i = mu_; i < lambda_; ++i)
    if (w[i] < 0) {
      const double sq = (inv_sqrt_C_ * y.col(i)).squaredNorm();
      w[i] = sq > 0 ? w[i] * n_ / sq : 0.0;
    }
  const double delta_h = hs ? 0.0 : cc_ * (2 - cc_);
  C_ = (1 + c1_ * delta_h - c1_ - cmu_ * w_.sum()) * C_ + c1_ * pc_ * pc_.transpose() +
       cmu_ * (y * w.asDiagonal() * y.transpose());
  sigma_ *= std::exp(std::min(1.0, cs_ / ds_ * (ps_norm / chi_n_ - 1)));
}

void CmaStrategy::decompose() {
  C_ = 0.5 * (C_ + C_.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(C_);
  const Eigen::VectorXd& values = eigen.eigenvalues();  // ascending
  // A rounding-level (or negative) eigenvalue is floored so that C^−1/2 exists; the condition test then stops.
  const double floor = std::max(values[n_ - 1], 0.0) * 1e-20 + std::numeric_limits<double>::min();
  D_ = values.cwiseMax(floor).cwiseSqrt();
  B_ = eigen.eigenvectors();
  inv_sqrt_C_ = B_ * D_.cwiseInverse().asDiagonal() * B_.transpose();
  decomposed_at_ = generation_;
}

void CmaStrategy::record(std::span<const double> values, const std::vector<int>& order) {
  const auto at = [&](int rank) { return ranked(values[order[static_cast<std::size_t>(rank)]]); };
  const int k = std::min(lambda_ - 1, static_cast<int>(std::ceil(0.1 + lambda_ / 4.0)));  // k-th best, 0-based
  bests_.push_back(at(0));
  medians_.push_back(at(lambda_ / 2));
  equal_best_.push_back(at(0) == at(k));
}

std::string_view CmaStrategy::first_stop(std::span<const double> values) const {
  const double max_generations = 100 + 150 * (n_ + 3.0) * (n_ + 3.0) / std::sqrt(lambda_);
  if (generation_ >= max_generations ||
      (tol_.max_evaluations > 0 && static_cast<long long>(generation_) * lambda_ >= tol_.max_evaluations))
    return "maxiter";
  if (flat_history(values)) return "tolfun";
  if (generation_ > n_) {
    const auto last = equal_best_.end() - n_;
    if (3 * std::count(last, equal_best_.end(), 1) > n_) return "equalfunvals";
  }
  const double tolx = tol_.tolx * sigma0_;
  if ((sigma_ * C_.diagonal().cwiseSqrt().array() < tolx).all() && (sigma_ * pc_.array().abs() < tolx).all())
    return "tolx";
  if (sigma_ / sigma0_ > 1e20 * D_.maxCoeff()) return "tolupsigma";
  if (stagnates()) return "stagnation";
  const double ratio = D_.maxCoeff() / D_.minCoeff();
  if (ratio * ratio > 1e14) return "conditioncov";
  if (no_effect_axis()) return "noeffectaxis";
  if (no_effect_coord()) return "noeffectcoord";
  return "";
}

bool CmaStrategy::flat_history(std::span<const double> values) const {
  const std::size_t window = 10 + static_cast<std::size_t>(std::ceil(30.0 * n_ / lambda_));
  if (bests_.size() < window) return false;
  double lo = kInf, hi = -kInf;
  for (auto it = bests_.end() - static_cast<std::ptrdiff_t>(window); it != bests_.end(); ++it)
    lo = std::min(lo, *it), hi = std::max(hi, *it);
  for (double v : values) lo = std::min(lo, ranked(v)), hi = std::max(hi, ranked(v));
  return std::isfinite(hi) && hi - lo < tol_.tolfun;
}

bool CmaStrategy::stagnates() const {
  const std::size_t count = bests_.size();
  const double least = 120 + 30.0 * n_ / lambda_;
  const auto window = static_cast<std::size_t>(std::min(20000.0, std::ceil(std::max(least, 0.2 * count))));
  if (count < window) return false;
  const auto newest = [&](const std::vector<double>& v) { return median_of(v.end() - 20, v.end()); };
  const auto oldest = [&](const std::vector<double>& v) {
    const auto first = v.end() - static_cast<std::ptrdiff_t>(window);
    return median_of(first, first + 20);
  };
  return newest(bests_) >= oldest(bests_) && newest(medians_) >= oldest(medians_);
}

bool CmaStrategy::no_effect_axis() const {
  const int i = generation_ % n_;
  return (m_ + 0.1 * sigma_ * D_[i] * B_.col(i)) == m_;
}

bool CmaStrategy::no_effect_coord() const {
  for (int j = 0; j < n_; ++j)
    if (m_[j] + 0.2 * sigma_ * std::sqrt(C_(j, j)) == m_[j]) return true;
  return false;
}

}  // namespace dampbench
