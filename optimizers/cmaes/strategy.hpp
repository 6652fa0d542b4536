#pragma once
// One CMA-ES run without restarts (Hansen 2016, "The CMA Evolution Strategy: A Tutorial", arXiv:1604.00772):
// the (μ/μ_W, λ)-CMA-ES with the tutorial's default parameters (its Table 1), negative weights (active
// covariance update) included:
//   μ = ⌊λ/2⌋,  w'_i = ln((λ + 1)/2) − ln i (i = 1 … λ),  μ_eff = (Σ_{i≤μ} w'_i)² / Σ_{i≤μ} w'_i²,
//   μ_eff⁻ the same over i > μ;  c_1 = 2 / ((n + 1.3)² + μ_eff);
//   c_μ = min(1 − c_1, 2 (μ_eff − 2 + 1/μ_eff) / ((n + 2)² + μ_eff));
//   w_i = w'_i / Σ_{j≤μ} w'_j for w'_i ≥ 0, else min(1 + c_1/c_μ, 1 + 2 μ_eff⁻/(μ_eff + 2),
//         (1 − c_1 − c_μ)/(n c_μ)) · w'_i / Σ_{j>μ} |w'_j|;
//   c_σ = (μ_eff + 2)/(n + μ_eff + 5),  d_σ = 1 + 2 max(0, sqrt((μ_eff − 1)/(n + 1)) − 1) + c_σ,
//   c_c = (4 + μ_eff/n)/(n + 4 + 2 μ_eff/n),  c_m = 1.
// Sampling x_k = m + σ B D z_k, z_k ~ N(0, I), with C = B D² Bᵀ from Eigen's SelfAdjointEigenSolver, decomposed
// again only when more than λ/(c_1 + c_μ)/n/10 evaluations (1/(c_1 + c_μ)/n/10 generations: every generation in
// small dimensions) have passed since the last time (the tutorial's O(n²) per sample).
// The update is the tutorial's (its "Summary"): mean, p_σ, p_c with the stall indicator h_σ, C with the
// rank-one and the weighted rank-μ terms (negative weights rescaled by n/‖C^−1/2 y‖²), then σ by cumulative
// step-size adaptation, its exponent clipped at 1 (σ grows at most e-fold per generation: a guard against an
// overflow of σ).
// Ranking: values sorted ascending, NaN and ±inf (failed candidates) last, ties to the lower sample index.
//
// Stopping tests (the tutorial's Appendix B.3 and pycma's defaults), checked after each update; the first
// that holds names the stop:
//   "maxiter"        generation ≥ 100 + 150 (n + 3)²/sqrt(λ), or the run's own evaluation cap (BIPOP);
//   "tolfun"         the range of the generation's values and of the best values of the last
//                    10 + ⌈30 n/λ⌉ generations is below tolfun;
//   "equalfunvals"   in more than 1/3 of the last n generations the best and the k-th best value (k = 1 +
//                    ⌈0.1 + λ/4⌉) are equal (a flat fitness);
//   "tolx"           σ·sqrt(C_ii) and σ·|p_c,i| are below tolx·σ₀ in every coordinate;
//   "tolupsigma"     σ/σ₀ > 1e20 · max D (a divergent step size);
//   "stagnation"     over the last max(120 + 30 n/λ, 20 % of the generations) (at most 20 000) generations the
//                    median of the newest 20 best and of the newest 20 median values is no lower than that of
//                    the oldest 20;
//   "conditioncov"   the condition number of C exceeds 1e14;
//   "noeffectaxis"   adding 0.1 σ D_i b_i (i = generation mod n) leaves the mean unchanged;
//   "noeffectcoord"  adding 0.2 σ sqrt(C_jj) leaves some coordinate of the mean unchanged.
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <Eigen/Dense>

namespace dampbench {

struct CmaTolerances {
  double tolfun = 1e-12;  ///< absolute, in the metric's units
  double tolx = 1e-12;    ///< relative to σ₀
  long long max_evaluations = 0;  ///< of this run; 0 = none
};

class CmaStrategy {
 public:
  /// A run of dimension n = mean.size() ≥ 1 with λ ≥ 2 samples per generation, step size sigma > 0.
  CmaStrategy(const Eigen::VectorXd& mean, double sigma, int lambda, const CmaTolerances& tolerances);

  [[nodiscard]] int lambda() const { return lambda_; }
  [[nodiscard]] int generation() const { return generation_; }
  [[nodiscard]] const Eigen::VectorXd& mean() const { return m_; }
  /// Writes the generation's λ samples as the columns of `samples`; sample k from the random stream
  /// (generation_key, k), n normal draws.
  void sample(std::uint64_t generation_key, Eigen::MatrixXd& samples);
  /// One generation's update from the samples and their values, in the order sampled.
  void update(const Eigen::MatrixXd& samples, std::span<const double> values);
  /// The stopping test that holds after the last update, or "" (names in the header comment).
  [[nodiscard]] std::string_view stop() const { return stop_; }

 private:
  void set_weights();
  void decompose();
  [[nodiscard]] std::vector<int> ranking(std::span<const double> values) const;
  void adapt(const Eigen::MatrixXd& y_sorted, const Eigen::VectorXd& y_w);
  void record(std::span<const double> values, const std::vector<int>& order);
  [[nodiscard]] std::string_view first_stop(std::span<const double> values) const;
  [[nodiscard]] bool flat_history(std::span<const double> values) const;
  [[nodiscard]] bool stagnates() const;
  [[nodiscard]] bool no_effect_axis() const;
  [[nodiscard]] bool no_effect_coord() const;

  int n_, lambda_, mu_;
  CmaTolerances tol_;
  double sigma0_;
  Eigen::VectorXd w_;  ///< all λ weights, the last ones negative
  double mueff_ = 0, cs_ = 0, ds_ = 0, cc_ = 0, c1_ = 0, cmu_ = 0, chi_n_ = 0;
  Eigen::VectorXd m_, ps_, pc_, D_;
  Eigen::MatrixXd C_, B_, inv_sqrt_C_;
  double sigma_;
  int generation_ = 0, decomposed_at_ = 0;
  std::vector<double> bests_, medians_;  ///< per generation (failures as +inf)
  std::vector<char> equal_best_;          ///< per generation: best == k-th best
  std::vector<std::uint64_t> sample_keys_, key_scratch_;  ///< sample()'s working storage
  std::vector<double> normals_, uniforms_;
  std::string_view stop_;
};

}  // namespace dampbench
