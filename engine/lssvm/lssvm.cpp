// LS-SVM damper model: regressors, normalization, training, one-step and free-run prediction, metrics
// (engine/lssvm/lssvm.hpp).
#include "engine/lssvm/lssvm.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/common/vector_math.hpp"

namespace dampbench::lssvm {

// ---- lags and regressors -------------------------------------------------------------------------------------

int Lags::first() const { return std::max({d, v, y}); }

Lags parse_lags(std::string_view text, std::string_view option) {
  Lags lags;
  constexpr int kMaxLag = 10000;
  for (const auto& [key, value] : parse_key_values(text, option)) {
    int* field = key == "d" ? &lags.d : key == "v" ? &lags.v : key == "y" ? &lags.y : nullptr;
    if (!field) throw InputError(fmt::format("{}: unknown key '{}' (expected d, v, y)", option, key));
    const ParsedNumber n = try_parse_number(value);
    if (n.status != NumberStatus::ok || n.value != std::floor(n.value) || n.value < 0 || n.value > kMaxLag)
      throw InputError(fmt::format("{} {}: expected a whole number from 0 to {}, got '{}'", option, key, kMaxLag, value));
    *field = static_cast<int>(n.value);
  }
  return lags;
}

std::string format_lags(const Lags& lags) { return fmt::format("d={},v={},y={}", lags.d, lags.v, lags.y); }

namespace {

double current_of(const Dataset& record) {
  const auto it = record.operating.find("I");
  return it == record.operating.end() ? 0.0 : it->second;
}

void check_length(const Dataset& record, const Lags& lags, std::string_view role) {
  const std::size_t needed = static_cast<std::size_t>(lags.first()) + 1;
  if (record.size() < needed)
    throw InputError(fmt::format("lssvm: {} record '{}' has {} samples; lags {} need at least {}", role, record.name,
                                 record.size(), format_lags(lags), needed));
}

void check_force(const Dataset& record, std::string_view role) {
  if (!record.has_force())
    throw DataError(fmt::format("lssvm: {} record '{}' has no force (F column); it is needed for {}", role, record.name,
                                 role == "training" ? "training" : "one-step prediction and the metrics"));
}

}  // namespace

void fill_regressor(const Dataset& record, const Lags& lags, std::span<const double> forces, std::size_t i,
                    double* out) {
  int p = 0;
  for (int k = 0; k <= lags.d; ++k) out[p++] = record.x_m[i - k];
  for (int k = 1; k <= lags.v; ++k) out[p++] = record.v_m_s[i - k];
  out[p++] = current_of(record);
  for (int k = 1; k <= lags.y; ++k) out[p++] = forces[i - k];
}

TrainingRows build_rows(std::span<const Dataset> records, const Lags& lags, int max_rows) {
  if (records.empty()) throw InputError("lssvm: empty training set (no training records)");
  if (max_rows < 0) throw InputError(fmt::format("--max-train: expected a whole number ≥ 0, got {}", max_rows));
  std::size_t total = 0;
  for (const Dataset& r : records) {
    check_force(r, "training");
    check_length(r, lags, "training");
    total += r.size() - static_cast<std::size_t>(lags.first());
  }
  const std::size_t keep = max_rows > 0 ? std::min<std::size_t>(total, static_cast<std::size_t>(max_rows)) : total;
  // Selected global row numbers ⌊k·T/keep⌋, increasing.
  std::vector<std::size_t> selected(keep);
  for (std::size_t k = 0; k < keep; ++k)
    selected[k] = static_cast<std::size_t>(std::uint64_t{k} * total / keep);  // k, T < 2³² (records in memory)

  TrainingRows rows;
  rows.available = static_cast<int>(total);
  rows.X.resize(lags.dim(), static_cast<Eigen::Index>(keep));
  rows.y.resize(static_cast<Eigen::Index>(keep));
  rows.record.resize(keep);
  rows.sample.resize(keep);
  std::size_t offset = 0, next = 0;
  for (std::size_t r = 0; r < records.size(); ++r) {
    const Dataset& rec = records[r];
    const std::size_t first = static_cast<std::size_t>(lags.first());
    const std::size_t count = rec.size() - first;
    for (; next < keep && selected[next] < offset + count; ++next) {
      const std::size_t i = first + (selected[next] - offset);
      const auto col = static_cast<Eigen::Index>(next);
      fill_regressor(rec, lags, rec.F_N, i, rows.X.col(col).data());
      rows.y[col] = rec.F_N[i];
      rows.record[next] = static_cast<int>(r);
      rows.sample[next] = i;
    }
    offset += count;
  }
  return rows;
}

// ---- normalization --------------------------------------------------------------------------------------------------

Normalizer Normalizer::fit(const Eigen::MatrixXd& X) {
  if (X.cols() == 0) throw InputError("lssvm: empty training set (no regressor rows)");
  Normalizer n;
  n.mean = X.rowwise().mean();
  n.scale.resize(X.rows());
  for (Eigen::Index j = 0; j < X.rows(); ++j) {
    const double var = (X.row(j).array() - n.mean[j]).square().mean();
    const double sd = std::sqrt(var);
    n.scale[j] = sd > 1e-12 * std::max(1.0, std::abs(n.mean[j])) ? sd : 1.0;
  }
  return n;
}

Eigen::MatrixXd Normalizer::apply(const Eigen::MatrixXd& X) const {
  Eigen::MatrixXd Z = X;
  for (Eigen::Index c = 0; c < Z.cols(); ++c) apply_in_place(Z.col(c).data());
  return Z;
}

void Normalizer::apply_in_place(double* x) const {
  for (Eigen::Index j = 0; j < mean.size(); ++j) x[j] = (x[j] - mean[j]) / scale[j];
}

// ---- model ----------------------------------------------------------------------------------------------------------

Model Model::train(const TrainingRows& rows, const Lags& lags, double c, double sigma) {
  if (rows.size() == 0) throw InputError("lssvm: empty training set (no regressor rows)");
  if (rows.X.rows() != lags.dim())
    throw InputError(fmt::format("lssvm: training rows have {} inputs but lags {} give {}", rows.X.rows(),
                                 format_lags(lags), lags.dim()));
  Model m;
  m.lags_ = lags;
  m.c_ = c;
  m.sigma_ = sigma;
  m.norm_ = Normalizer::fit(rows.X);
  m.X_ = m.norm_.apply(rows.X);
  m.coef_ = solve_bordered(rbf_kernel(m.X_, sigma), rows.y, c);
  return m;
}

Model Model::from_parts(const Lags& lags, double c, double sigma, Normalizer norm, Eigen::MatrixXd points,
                        Coefficients coef) {
  const Eigen::Index dim = lags.dim();
  if (points.rows() != dim || norm.mean.size() != dim || norm.scale.size() != dim)
    throw InputError(fmt::format("lssvm model: lags {} give {} inputs, but the points have {} and the normalizer {}",
                                 format_lags(lags), dim, points.rows(), norm.mean.size()));
  if (points.cols() == 0 || coef.alpha.size() != points.cols())
    throw InputError(fmt::format("lssvm model: {} training points but {} coefficients alpha", points.cols(),
                                 coef.alpha.size()));
  if (!(c > 0) || !std::isfinite(c) || !(sigma > 0) || !std::isfinite(sigma))
    throw InputError(fmt::format("lssvm model: c and sigma must be positive, got c = {}, sigma = {}", c, sigma));
  Model m;
  m.lags_ = lags;
  m.c_ = c;
  m.sigma_ = sigma;
  m.norm_ = std::move(norm);
  m.X_ = std::move(points);
  m.coef_ = std::move(coef);
  return m;
}

namespace {

/// f at a normalized regressor x; scratch holds N doubles.
double evaluate(const Eigen::MatrixXd& X, const Coefficients& coef, double sigma, const double* x, double* scratch) {
  const Eigen::Index n = X.cols();
  rbf_kernel_column(X, x, 1.0 / (sigma * sigma), scratch, n);
  double f = 0;
  for (Eigen::Index j = 0; j < n; ++j) f += coef.alpha[j] * scratch[j];
  return f + coef.b;
}

}  // namespace

double Model::predict(std::span<const double> raw_regressor) const {
  if (static_cast<int>(raw_regressor.size()) != lags_.dim())
    throw InputError(fmt::format("lssvm: regressor of length {}, expected {}", raw_regressor.size(), lags_.dim()));
  std::vector<double> x(raw_regressor.begin(), raw_regressor.end());
  norm_.apply_in_place(x.data());
  std::vector<double> scratch(static_cast<std::size_t>(X_.cols()));
  return evaluate(X_, coef_, sigma_, x.data(), scratch.data());
}

std::vector<double> Model::predict_one_step(const Dataset& record) const {
  check_force(record, "test");
  check_length(record, lags_, "test");
  std::vector<double> out = record.F_N;
  std::vector<double> x(static_cast<std::size_t>(lags_.dim())), scratch(static_cast<std::size_t>(X_.cols()));
  for (std::size_t i = static_cast<std::size_t>(lags_.first()); i < record.size(); ++i) {
    fill_regressor(record, lags_, record.F_N, i, x.data());
    norm_.apply_in_place(x.data());
    out[i] = evaluate(X_, coef_, sigma_, x.data(), scratch.data());
  }
  return out;
}

std::size_t free_run(const Eigen::MatrixXd& X, const Coefficients& coef, double sigma, const Normalizer& norm,
                     const Lags& lags, const Dataset& record, std::size_t from, std::size_t to,
                     std::span<double> forces, double bound) {
  std::vector<double> x(static_cast<std::size_t>(lags.dim())), scratch(static_cast<std::size_t>(X.cols()));
  for (std::size_t i = from; i < to; ++i) {
    fill_regressor(record, lags, forces, i, x.data());
    norm.apply_in_place(x.data());
    const double f = evaluate(X, coef, sigma, x.data(), scratch.data());
    if (!(std::abs(f) <= bound)) return i;
    forces[i] = f;
  }
  return to;
}

std::vector<double> Model::simulate(const Dataset& record) const {
  check_length(record, lags_, "test");
  std::vector<double> out(record.size(), 0.0);
  const std::size_t first = static_cast<std::size_t>(lags_.first());
  if (record.has_force()) std::copy_n(record.F_N.begin(), first, out.begin());
  // Stops only at a NaN force, after which every force would be NaN: the metrics show it as it is.
  const std::size_t end = free_run(X_, coef_, sigma_, norm_, lags_, record, first, record.size(), out);
  std::fill(out.begin() + static_cast<std::ptrdiff_t>(end), out.end(), std::nan(""));
  return out;
}

// ---- metrics ----------------------------------------------------------------------------------------------------------

void MetricAccumulator::add(std::span<const double> measured, std::span<const double> predicted, std::size_t from) {
  const std::size_t n = std::min(measured.size(), predicted.size());
  for (std::size_t i = from; i < n; ++i) {
    const double e = measured[i] - predicted[i];
    sum_sq_ += e * e;
    sum_abs_ += std::abs(e);
    max_abs_ = std::max(max_abs_, std::abs(e));
    max_force_ = std::max(max_force_, std::abs(measured[i]));
    if (!std::isfinite(e)) max_abs_ = e;  // a non-finite prediction must show, not vanish in std::max
  }
  if (n > from) n_ += n - from;
}

ErrorMetrics MetricAccumulator::finish() const {
  ErrorMetrics m;
  m.samples = n_;
  if (n_ == 0) return m;
  const double n = static_cast<double>(n_);
  m.mse = sum_sq_ / n;
  m.mae = sum_abs_ / n;
  m.max_abs = std::isfinite(max_abs_) ? max_abs_ : std::numeric_limits<double>::infinity();
  m.max_rel = max_force_ > 0 ? m.max_abs / max_force_ : std::numeric_limits<double>::infinity();
  m.nrmse = max_force_ > 0 ? std::sqrt(m.mse) / max_force_ : std::numeric_limits<double>::infinity();
  return m;
}

// ---- fitness names -------------------------------------------------------------------------------------------------------

Fitness parse_fitness(std::string_view text) {
  if (text == "validation" || text.empty()) return Fitness::validation;
  if (text == "paper") return Fitness::paper;
  if (text == "free-run") return Fitness::free_run;
  throw InputError(fmt::format("--fitness: expected validation, paper or free-run, got '{}'", text));
}

std::string_view fitness_name(Fitness f) {
  switch (f) {
    case Fitness::paper: return "paper";
    case Fitness::free_run: return "free-run";
    case Fitness::validation: break;
  }
  return "validation";
}

}  // namespace dampbench::lssvm
