#pragma once
// LS-SVM NARX damper model (lssvm paper: Qian, Yin & Ouyang 2021, Int. J. Aerospace Eng. 6648749;
// docs/models.md (lssvm)): displacement, velocity, current and past forces in, force out.
//
// Regressor at sample i (eq. 1 with the past outputs of §4.2; lag orders are settings, Lags):
//   x_i = [d_i, d_{i−1}, …, d_{i−nd},  v_{i−1}, …, v_{i−nv},  I,  y_{i−1}, …, y_{i−ny}]
// d displacement [m], v velocity [m/s], I the record's operating variable "I" [A] (0 when absent), y force [N].
// Every column is normalized by the mean and the (population) standard deviation of the training rows only;
// a column that is constant in training (e.g. I when every training record has the same current) is only
// centred. The output y_i is the force in N, not normalized (LS-SVM is equivariant to the scale of y).
//
// Model (eqs. 6–7): f(x) = Σ_j α_j K(x_j, x) + b,  K(x_j, x) = exp(−‖x_j − x‖²/σ²)  (σ in normalized units).
// Training, regression form of eq. 5 (the printed y_i·y_j factors are the classification form; docs/models.md (lssvm)):
//   [[0, 1ᵀ], [1, K + I/c]]·[b; α] = [0; y]
// solved as two solves with H = K + I/c (SPD): η = H⁻¹1, ν = H⁻¹y, b = 1ᵀν / 1ᵀη, α = ν − b·η.
// For one σ and many c, SpectralFactor reuses one eigendecomposition K = QΛQᵀ:
//   H⁻¹ = Q diag(1/(λ + 1/c)) Qᵀ, so with u = Qᵀy, w = Qᵀ1, d_k = 1/(λ_k + 1/c):
//   b = Σ d_k w_k u_k / Σ d_k w_k²,  g = Qᵀα = d ⊙ (u − b·w),  training residual y − f = α/c,
//   training SSE = ‖g‖²/c², predictions at other points f = (K_cross Q) g + b.
//
// Prediction of a record (its first L = Lags::first() forces are the initial conditions, taken from the
// measurement; predictions and metrics start at sample L):
//   one-step-ahead: y_{i−k} in x_i are the measured forces;
//   free run (simulation): y_{i−k} are the model's own earlier outputs (what a controller uses).
//
// Hyperparameters (c, σ) by the project's GA, or PSO for the free-run fitness (tune()); see TuneSettings for the fitness, the validation split,
// the bounds and the σ grid.
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Dense>

#include "engine/record/dataset.hpp"

namespace dampbench::lssvm {

// ---- regressors ------------------------------------------------------------------------------------------

/// Lag orders. Defaults d = 2, v = 2, y = 2: the paper does not print its orders. On the synthetic set
/// (datasets/lssvm) d=v=y=1 doubles the free-run MSE, d=v=y=3 gains ~10 %, and v = 0 makes the free run
/// drift (the model must then infer the velocity from displacements only).
struct Lags {
  int d = 2;  ///< displacements d_i … d_{i−d}: d + 1 values (d_i always included)
  int v = 2;  ///< past velocities v_{i−1} … v_{i−v}
  int y = 2;  ///< past forces y_{i−1} … y_{i−y} (0: a static map, one-step = free run)

  /// Regressor length: (d + 1) + v + 1 (I) + y.
  [[nodiscard]] int dim() const { return d + 1 + v + 1 + y; }
  /// First sample with a complete regressor: max(d, v, y).
  [[nodiscard]] int first() const;
};

/// Parses "d=2,v=2,y=2" (keys optional, each a whole number ≥ 0; missing keys keep the defaults).
/// InputError: "--lags: unknown key 'z' (expected d, v, y)", "--lags d: expected a whole number ≥ 0, got '-1'".
Lags parse_lags(std::string_view text, std::string_view option = "--lags");
std::string format_lags(const Lags& lags);  ///< "d=2,v=2,y=2"

/// Writes the raw (SI, not normalized) regressor of sample i (Lags::first() ≤ i < n) into out[0 .. dim),
/// with the past forces taken from `forces` (measured for one-step, simulated for free run).
void fill_regressor(const Dataset& record, const Lags& lags, std::span<const double> forces, std::size_t i,
                    double* out);

/// Training rows in raw units: X is dim × N (one column per sample), y the N measured forces.
struct TrainingRows {
  Eigen::MatrixXd X;
  Eigen::VectorXd y;
  std::vector<int> record;  ///< index of the record each column comes from (columns in time order per record)
  std::vector<std::size_t> sample;  ///< the sample of its record each column is the regressor of
  int available = 0;        ///< rows the records give before the max_rows cap
  [[nodiscard]] int size() const { return static_cast<int>(y.size()); }
};

/// Regressor rows of every record (force required). With max_rows > 0 and more rows than that, keeps
/// max_rows of them evenly spaced over the concatenation: row ⌊k·T/max_rows⌋ for k = 0 … max_rows − 1.
/// InputError: no records, a record without force, a record shorter than its lags
/// ("lssvm: record 'a' has 3 samples; lags d=2,v=2,y=5 need at least 6").
TrainingRows build_rows(std::span<const Dataset> records, const Lags& lags, int max_rows = 0);

/// Column statistics of the training rows; apply() maps raw regressors to normalized ones.
struct Normalizer {
  Eigen::VectorXd mean, scale;  ///< scale = standard deviation, or 1 for a constant column
  static Normalizer fit(const Eigen::MatrixXd& X);
  [[nodiscard]] Eigen::MatrixXd apply(const Eigen::MatrixXd& X) const;
  void apply_in_place(double* x) const;
};

// ---- kernel and solvers ------------------------------------------------------------------------------------

/// K_ij = exp(−‖a_i − b_j‖²/σ²) for the columns a_i of A (dim × M) and b_j of B (dim × N): an M × N matrix.
/// InputError for σ ≤ 0 or not finite ("lssvm: sigma must be positive, got 0").
Eigen::MatrixXd rbf_kernel(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double sigma);
/// The symmetric N × N kernel matrix of the columns of X (exact zero distance on the diagonal: K_ii = 1).
Eigen::MatrixXd rbf_kernel(const Eigen::MatrixXd& X, double sigma);
/// exp(−‖A_i − b‖² · inv_sigma2) for the columns i < count of A, into out[0 .. count): one kernel row.
void rbf_kernel_column(const Eigen::MatrixXd& A, const double* b, double inv_sigma2, double* out, Eigen::Index count);

/// Coefficients of f(x) = Σ α_j K(x_j, x) + b.
struct Coefficients {
  double b = 0;
  Eigen::VectorXd alpha;
};

/// The bordered system by one Cholesky factorization of K + I/c and two solves (see the file comment).
/// InputError: c ≤ 0 or not finite ("lssvm: c must be positive, got -1"), size mismatch, an empty system.
Coefficients solve_bordered(const Eigen::MatrixXd& K, const Eigen::VectorXd& y, double c);
/// The same, factorizing K's storage in place (for a kernel matrix made just for this solve).
Coefficients solve_bordered(Eigen::MatrixXd&& K, const Eigen::VectorXd& y, double c);

/// One eigendecomposition K = QΛQᵀ for a fixed σ, reused for any c (see the file comment).
/// The symmetric QR algorithm (Golub & Van Loan, Alg. 8.3.3: Householder tridiagonalization, implicit QR
/// steps with the Wilkinson shift) applies its rotations only to the vectors it needs — y, 1 and the
/// rows of `cross` — unless keep_vectors asks for all of Q. Cost O(N³) once (tridiagonalization), then
/// O(N) per c for the training SSE, O(M·N) for M cross predictions and O(N²) for α (keep_vectors).
class SpectralFactor {
 public:
  /// K: N × N kernel matrix; y: N targets; cross: M × N kernel between M other points and the N training
  /// points (0 × 0 for none). Same checks as solve_bordered. ok() is false if the QR iteration did not
  /// converge (30·N steps, as Eigen's SelfAdjointEigenSolver).
  SpectralFactor(const Eigen::MatrixXd& K, const Eigen::VectorXd& y, const Eigen::MatrixXd& cross = {},
                 bool keep_vectors = false);

  [[nodiscard]] bool ok() const { return ok_; }
  [[nodiscard]] int size() const { return static_cast<int>(lambda_.size()); }
  [[nodiscard]] const Eigen::VectorXd& eigenvalues() const { return lambda_; }  ///< unsorted
  /// Bytes held: (2 + M [+ N]) × N + N doubles.
  [[nodiscard]] std::size_t memory_bytes() const {
    return sizeof(double) * static_cast<std::size_t>(rotated_.size() + lambda_.size());
  }
  [[nodiscard]] double bias(double c) const;
  /// Σ_i (y_i − f(x_i))² over the training points = ‖α‖²/c².
  [[nodiscard]] double training_sse(double c) const;
  /// f at the M cross points.
  [[nodiscard]] Eigen::VectorXd cross_predictions(double c) const;
  /// Σ_j (y_cross_j − f(cross point j))².
  [[nodiscard]] double cross_sse(double c, const Eigen::VectorXd& y_cross) const;
  /// b and α (needs keep_vectors; InputError otherwise).
  [[nodiscard]] Coefficients solve(double c) const;

 private:
  /// g = Qᵀα = d ⊙ (u − b·w) and b, for one c.
  double coefficients_in_eigenbasis(double c, Eigen::VectorXd& g) const;

  bool ok_ = false;
  int cross_rows_ = 0;
  bool keep_vectors_ = false;
  Eigen::VectorXd lambda_;
  /// Rows: uᵀ = (Qᵀy)ᵀ, wᵀ = (Qᵀ1)ᵀ, then the M rows of K_cross·Q, then (keep_vectors) the N rows of Q.
  Eigen::MatrixXd rotated_;
};

// ---- the model ---------------------------------------------------------------------------------------------

class Model {
 public:
  /// Normalizes the rows with their own statistics and solves the bordered system.
  static Model train(const TrainingRows& rows, const Lags& lags, double c, double sigma);
  /// A trained model from its parts as train() left them (a model file read back: engine/fit/lssvm_model_file.hpp).
  /// InputError when the sizes disagree (lags' dimension, normalizer, points, coefficients).
  static Model from_parts(const Lags& lags, double c, double sigma, Normalizer norm, Eigen::MatrixXd points,
                          Coefficients coef);

  [[nodiscard]] const Lags& lags() const { return lags_; }
  [[nodiscard]] double c() const { return c_; }
  [[nodiscard]] double sigma() const { return sigma_; }
  [[nodiscard]] const Coefficients& coefficients() const { return coef_; }
  [[nodiscard]] const Normalizer& normalizer() const { return norm_; }
  [[nodiscard]] const Eigen::MatrixXd& points() const { return X_; }  ///< normalized training points, dim × N

  /// f at one raw regressor (dim values, SI).
  [[nodiscard]] double predict(std::span<const double> raw_regressor) const;
  /// One-step-ahead force of every sample (samples before Lags::first() are the measured forces).
  /// InputError for a record without force or shorter than the lags.
  [[nodiscard]] std::vector<double> predict_one_step(const Dataset& record) const;
  /// Free-run force of every sample (the first Lags::first() forces are the measured initial conditions).
  [[nodiscard]] std::vector<double> simulate(const Dataset& record) const;

 private:
  Lags lags_;
  double c_ = 0, sigma_ = 0;
  Normalizer norm_;
  Eigen::MatrixXd X_;  ///< normalized training points, dim × N
  Coefficients coef_;
};

/// Free run with the model (X normalized training points, coef, sigma, norm): forces[i] for from ≤ i < to from the
/// model's own earlier outputs, forces[i < from] the initial conditions (Lags::first() ≤ from). The one loop behind
/// Model::simulate and the free-run fitness. Stops at the first force that is NaN or exceeds `bound` in magnitude
/// (a free run that diverges), without storing it, and returns its sample; `to` when every force was stored.
std::size_t free_run(const Eigen::MatrixXd& X, const Coefficients& coef, double sigma, const Normalizer& norm,
                     const Lags& lags, const Dataset& record, std::size_t from, std::size_t to,
                     std::span<double> forces, double bound = std::numeric_limits<double>::infinity());

// ---- metrics -------------------------------------------------------------------------------------------------

/// Errors e = F_measured − F_model over the predicted samples of one or several records (pooled).
struct ErrorMetrics {
  double mse = 0;      ///< Σe²/n [N²] (the paper's Table 1)
  double mae = 0;      ///< Σ|e|/n [N] (the paper's "average error")
  double max_abs = 0;  ///< max|e| [N] (the paper's "maximum error")
  double max_rel = 0;  ///< max|e| / max|F_measured|: the paper's "maximum relative error" read relative to the
                       ///< force amplitude (|e_i|/|F_i| point by point is unbounded where F crosses zero)
  double nrmse = 0;    ///< sqrt(mse) / max|F_measured|, as engine/model/metrics.hpp
  std::size_t samples = 0;
};

/// Accumulates sums in the order samples are added; finish() gives the metrics (all 0 for no samples).
class MetricAccumulator {
 public:
  void add(std::span<const double> measured, std::span<const double> predicted, std::size_t from = 0);
  [[nodiscard]] ErrorMetrics finish() const;

 private:
  double sum_sq_ = 0, sum_abs_ = 0, max_abs_ = 0, max_force_ = 0;
  std::size_t n_ = 0;
};

// ---- hyperparameters by GA -------------------------------------------------------------------------------------

enum class Fitness {
  /// Default: one-step MSE on held-out rows. The last `validation_fraction` of each training record's rows
  /// (in time order, a contiguous block per record) is held out; the model is fitted on the rest. A
  /// contiguous block, not random rows: neighbouring samples of a record are nearly equal, so randomly held-out
  /// rows would reward interpolation just as the training error does.
  validation,
  /// The paper's eq. 8: maximize F = 1/(SSE + 1e−6) with SSE the training error on all training rows
  /// (minimizes SSE; same ranking). It rewards interpolation: it drives c to its upper bound and σ down to
  /// the scale of the distance between neighbouring samples (test_lssvm.cpp shows it), where the model
  /// reproduces its training forces and generalizes poorly. Kept for comparison with the paper.
  paper,
  /// Free-run MSE on the held-out tails (what a controller uses): the model is fitted on the same rows
  /// as `validation`, then simulates each training record at its full rate (the lags are in record samples)
  /// from its first held-out sample to its end, starting from the measured forces before it. A free run that
  /// diverges (|F| > 10 × the largest training force) scores +inf. Each candidate costs a kernel matrix and a
  /// Cholesky solve of the fitted rows (~0.25 s at 1 600 rows), far more than the validation fitness's shared
  /// eigendecompositions: it is searched by PSO with a smaller budget (tune(), lssvm_command.cpp).
  free_run,
};
Fitness parse_fitness(std::string_view text);  ///< "validation" | "paper" | "free-run"; InputError otherwise
std::string_view fitness_name(Fitness f);

struct TuneSettings {
  Fitness fitness = Fitness::validation;
  double validation_fraction = 0.2;  ///< held-out tail of each training record (Fitness::validation)
  int population = 50;               ///< lssvm paper §3
  int generations = 500;             ///< lssvm paper §3 (generation 0 included: 25 000 evaluations)
  double pc = 0.6;                   ///< crossover probability (paper §3; = `ga` preset lssvm)
  double pm = 0.03;                  ///< mutation probability per gene (paper §3)
  /// Search box. The paper's open intervals c ∈ (0, 100), σ ∈ (0, 10) closed at small positive values;
  /// the GA searches c and σ linearly, as the paper.
  double c_min = 1e-3, c_max = 100, sigma_min = 1e-2, sigma_max = 10;
  /// σ is rounded to a logarithmic grid of this many points per decade (64: neighbours 3.7 % apart) so that
  /// candidates that share a grid σ share one eigendecomposition; c stays continuous. The reported σ is the
  /// grid value.
  int sigma_per_decade = 64;
  std::uint64_t seed = 1;
};

/// The training records and lags the rows were built from: Fitness::free_run simulates the records themselves.
struct TrainingRecords {
  std::span<const Dataset> records;
  Lags lags;
};

struct TuneResult {
  double c = 0, sigma = 0;
  double objective = 0;      ///< minimized value: validation or free-run MSE [N²], or training SSE [N²] (paper)
  int fit_rows = 0, validation_rows = 0;
  long long free_run_samples = 0;  ///< samples one free-run fitness simulates (Fitness::free_run)
  int factorizations = 0;    ///< eigendecompositions computed (distinct grid σ, recomputations included)
  long long evaluations = 0;
  std::vector<double> best_history;  ///< best objective after each generation
};

/// σ rounded to the grid: 10^(round(k·log10 σ)/k), k = per_decade.
double snap_sigma(double sigma, int per_decade);

/// Runs the GA (optimizers/registry `ga` with pc, pm, population and generations of the settings) on the
/// training rows. Each generation is one batch: the distinct grid σ not yet cached are decomposed in
/// parallel, then every candidate is evaluated in parallel (oneTBB); a candidate's value depends only on
/// (c, grid σ), so results are bit-identical for any thread count. InputError for bad settings or too few rows.
/// Fitness::free_run runs PSO (optimizers/registry `pso`, population × generations iterations) over log10 c and
/// log10 σ instead, one model per candidate, and needs `records` (InputError without them).
TuneResult tune(const TrainingRows& rows, const TuneSettings& settings, const TrainingRecords& records = {});

/// The objective tune() minimizes, for one (c, σ) (the same code path as tune(); for tests and scans).
double objective(const TrainingRows& rows, const TuneSettings& settings, double c, double sigma,
                 const TrainingRecords& records = {});

}  // namespace dampbench::lssvm
