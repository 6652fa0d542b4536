#include "optimizers/cmaes/cmaes.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "optimizers/cmaes/bound_transform.hpp"

namespace dampbench {

CmaesRestarts parse_cmaes_restarts(std::string_view name) {
  if (name == "none") return CmaesRestarts::none;
  if (name == "ipop") return CmaesRestarts::ipop;
  if (name == "bipop") return CmaesRestarts::bipop;
  throw InputError(fmt::format("cmaes: unknown restarts '{}' (known: none, ipop, bipop)", name));
}

std::string_view cmaes_restarts_name(CmaesRestarts restarts) {
  switch (restarts) {
    case CmaesRestarts::none: return "none";
    case CmaesRestarts::ipop: return "ipop";
    case CmaesRestarts::bipop: return "bipop";
  }
  return "?";
}

void CmaesSettings::validate() const {
  if (population != 0 && population < 2)
    throw InputError(fmt::format(
        "cmaes: population must be 0 (the default 4 + floor(3 ln n)) or at least 2, got {}", population));
  if (generations < 1) throw InputError(fmt::format("cmaes: iterations must be at least 1, got {}", generations));
  check_ranges("cmaes", cmaes_setting_table(), *this);
}

const SettingTable<CmaesSettings>& cmaes_setting_table() {
  static const SettingTable<CmaesSettings> table{
      {"sigma0", &CmaesSettings::sigma0, {0, 1, true}, "initial step size, as a fraction of every parameter's range"},
      {"tolfun", &CmaesSettings::tolfun, kNonNegative,
       "a run stops when its recent best and current values lie within this range (metric units)"},
      {"tolx", &CmaesSettings::tolx, kNonNegative,
       "a run stops when its steps fall below this fraction of its initial step size"},
  };
  return table;
}

int cmaes_default_population(int free_parameters) {
  return 4 + static_cast<int>(std::floor(3 * std::log(static_cast<double>(std::max(1, free_parameters)))));
}

Cmaes::Cmaes(const CmaesSettings& settings, const Bounds& bounds, std::uint64_t run_key)
    : settings_(validated(settings)), box_(bounds), run_key_(run_key), dim_(bounds.dim()),
      n_(std::max(1, box_.free_dim())),
      batch_(settings.population > 0 ? settings.population : cmaes_default_population(n_)) {
  if (static_cast<int>(bounds.start.size()) == dim_) start_ = bounds.start;
  best_position_.resize(static_cast<std::size_t>(dim_));
  sampling_ = start_.empty();
  std::vector<double> y(static_cast<std::size_t>(n_), 0.5);
  if (!sampling_) {
    start_run();
    for (int i = 0; i < n_; ++i) y[i] = to_phenotype(strategy_->mean()[i]);
  }
  box_.to_params(y, best_position_);  // the first mean (or the box's centre), until a value is told
}

void Cmaes::draw_uniform_sample() {
  RandomStream rng(hash_key({run_key_, ~std::uint64_t{0}}));
  sample_unit_.resize(static_cast<std::size_t>(batch_) * n_);
  for (double& u : sample_unit_) u = rng.uniform();
}

void Cmaes::write_asked(std::span<const double> unit, CandidateBatch& batch, int first) {
  asked_.resize(static_cast<std::size_t>(batch_) * dim_);
  for (int i = 0; i < batch_; ++i) {
    const std::span<const double> y = unit.subspan(static_cast<std::size_t>(i) * n_, static_cast<std::size_t>(n_));
    const std::span<double> x(asked_.data() + static_cast<std::size_t>(i) * dim_, static_cast<std::size_t>(dim_));
    box_.to_params(y, x);
    for (int j = 0; j < dim_; ++j) batch.at(first + i, j) = x[j];
  }
}

void Cmaes::start_from_sample(std::span<const double> values) {
  sampling_ = false;
  int best = -1;
  for (int i = 0; i < batch_; ++i)
    if (std::isfinite(values[i]) && (best < 0 || values[i] < values[best])) best = i;
  if (best < 0) {  // every point failed: the drawn mean is as good a start as any
    start_run();
    return;
  }
  Eigen::VectorXd mean(n_);
  for (int j = 0; j < n_; ++j) mean[j] = to_genotype(sample_unit_[static_cast<std::size_t>(best) * n_ + j]);
  start_run(&mean);
}

Eigen::VectorXd Cmaes::initial_mean(RandomStream& rng) const {
  std::vector<double> y(static_cast<std::size_t>(n_));
  for (double& v : y) v = rng.uniform();  // drawn also when start_ replaces them: later draws keep their place
  if (runs_.empty() && !start_.empty()) {
    const std::vector<double> unit = box_.to_unit(start_);
    std::copy(unit.begin(), unit.end(), y.begin());
  }
  Eigen::VectorXd g(n_);
  for (int i = 0; i < n_; ++i) g[i] = to_genotype(y[i]);
  return g;
}

void Cmaes::start_run(const Eigen::VectorXd* given_mean) {
  const auto r = static_cast<std::uint64_t>(runs_.size());
  RandomStream rng(hash_key({run_key_, r, 0}));
  Eigen::VectorXd mean = initial_mean(rng);  // drawn also when replaced: later draws keep their place
  if (given_mean) mean = *given_mean;
  // λ never needs to exceed the whole budget: a generation larger than it is never completed.
  const auto capped = [&](double lambda) {
    const double asks = std::min(std::ceil(lambda / batch_), static_cast<double>(settings_.generations));
    return batch_ * static_cast<int>(asks);
  };
  const double lambda_large = batch_ * std::pow(2.0, large_runs_);
  CmaesRun run{capped(lambda_large), settings_.sigma0, true, 0, {}};
  CmaTolerances tol{settings_.tolfun, settings_.tolx, 0};
  if (settings_.restarts == CmaesRestarts::bipop && r > 0 && small_evaluations_ < large_evaluations_) {
    const double u1 = rng.uniform(), u2 = rng.uniform();
    run = {capped(std::floor(batch_ * std::pow(0.5 * lambda_large / batch_, u1 * u1))),
           settings_.sigma0 * std::pow(10.0, -2 * u2), false, 0, {}};
    for (auto it = runs_.rbegin(); it != runs_.rend(); ++it)
      if (it->large) {
        tol.max_evaluations = std::max(1LL, it->evaluations / 2);
        break;
      }
  } else {
    ++large_runs_;
  }
  runs_.push_back(run);
  strategy_.emplace(mean, run.sigma0, run.lambda, tol);
  values_.assign(static_cast<std::size_t>(run.lambda), 0.0);
  told_ = 0;
}

void Cmaes::ask(CandidateBatch& batch, int first) {
  if (sampling_) {
    draw_uniform_sample();
    write_asked(sample_unit_, batch, first);
    return;
  }
  if (told_ == 0) {
    const auto r = static_cast<std::uint64_t>(runs_.size() - 1);
    strategy_->sample(hash_key({run_key_, r, static_cast<std::uint64_t>(strategy_->generation() + 1)}), samples_);
  }
  // Samples told_ … told_ + batch − 1 are consecutive columns: one contiguous run of batch × n genotypes.
  asked_unit_.resize(static_cast<std::size_t>(batch_) * n_);
  to_phenotypes({samples_.col(told_).data(), asked_unit_.size()}, asked_unit_);
  write_asked(asked_unit_, batch, first);
}

void Cmaes::tell(std::span<const double> values) {
  assert(static_cast<int>(values.size()) == batch_);
  for (int i = 0; i < batch_; ++i) {
    if (!sampling_) values_[static_cast<std::size_t>(told_ + i)] = values[i];
    if (std::isfinite(values[i]) && values[i] < best_value_) {
      best_value_ = values[i];
      std::copy_n(asked_.begin() + static_cast<std::ptrdiff_t>(i) * dim_, dim_, best_position_.begin());
    }
  }
  ++asks_;
  if (sampling_) {
    start_from_sample(values);
    return;
  }
  told_ += batch_;
  if (told_ == strategy_->lambda()) end_generation();
}

void Cmaes::end_generation() {
  strategy_->update(samples_, values_);
  told_ = 0;
  CmaesRun& run = runs_.back();
  run.evaluations += run.lambda;
  if (strategy_->stop().empty()) return;
  run.stop = strategy_->stop();
  if (runs_.size() > 1) (run.large ? large_evaluations_ : small_evaluations_) += run.evaluations;
  if (settings_.restarts == CmaesRestarts::none) ended_ = true;
  else start_run();
}

}  // namespace dampbench
