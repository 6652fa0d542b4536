// LawModel::stepper(): a law model stepped sample by sample (engine/model/stepper.hpp), its laws evaluated at the
// variables each set_parameters gives, with each driver lag's u integrated between, and its base model stepped.
#include "engine/model/law_model.hpp"

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {
namespace {

/// With driver lags, the laws see the lagged u of each commanded variable: over a sub-step of length h under the
/// held command c, u moves exactly as c + (u − c)·e^(−t/τ); the base takes one RK4 sub-step with the laws at u of
/// the sub-step's middle, and the force at a sample sees u there. The C export (engine/export) does the same.
/// A base that reads the variables itself (fdsp's filter reads V in its context) gets them with the lagged values.
class LawStepper final : public ModelStepper {
 public:
  LawStepper(const LawModel& model, std::unique_ptr<ModelStepper> base)
      : model_(model), base_(std::move(base)), lagged_(model.lags().size(), 0.0), tau_(model.lags().size(), 0.0),
        commands_(model.lags().size(), 0.0) {}

  void set_parameters(std::span<const double> coefficients, const std::map<std::string, double>& variables) override {
    coefficients_.assign(coefficients.begin(), coefficients.end());
    commanded_ = seen_ = variables;
    for (std::size_t i = 0; i < tau_.size(); ++i) {
      const auto& lag = model_.lags()[i];
      tau_[i] = model_.lag_tau(lag, coefficients);
      if (!(tau_[i] >= 0)) throw InputError(fmt::format("{}: the driver lag's tau must be >= 0 s, got {}", model_.id(), tau_[i]));
      const auto it = variables.find(lag.variable);
      commands_[i] = it == variables.end() ? std::nan("") : it->second;
    }
    base_values_ = model_.base_parameters(coefficients_, commanded_);  // InputError for a variable the laws lack
    plan_lagged_laws();
    apply(lagged_, true);
  }
  void set_parameter_values(std::span<const double> coefficients) override { set_parameters(coefficients, commanded_); }
  [[nodiscard]] bool reads_variables() const override { return true; }
  void reset() override {
    base_->reset();
    lagged_ = commands_;  // u(0) = c(0)
    apply(lagged_);
  }
  [[nodiscard]] double force(double x, double v, double a) const override { return base_->force(x, v, a); }
  [[nodiscard]] double stiffness(double velocity_max_abs_m_s, double displacement_ptp_m) const override {
    return base_->stiffness(velocity_max_abs_m_s, displacement_ptp_m);
  }
  [[nodiscard]] int kernel_substeps(const Signals& data, std::size_t k, double lambda) const override {
    return base_->kernel_substeps(data, k, lambda);
  }
  void advance(double x0, double v0, double x1, double v1, double dt, int substeps) override {
    if (lagged_.empty()) return base_->advance(x0, v0, x1, v1, dt, substeps);
    const double inv = 1.0 / substeps, h = dt * inv, dx = x1 - x0, dv = v1 - v0;
    middle_.resize(lagged_.size());
    decay_half_.resize(lagged_.size());
    decay_.resize(lagged_.size());
    for (std::size_t j = 0; j < lagged_.size(); ++j) {  // the same h at every sub-step of the interval
      decay_half_[j] = std::exp(-(0.5 * h) / tau_[j]);
      decay_[j] = std::exp(-h / tau_[j]);
    }
    for (int i = 0; i < substeps; ++i) {
      const double a = i * inv, b = (i + 1) * inv;
      for (std::size_t j = 0; j < lagged_.size(); ++j) {
        const double c = commands_[j];
        middle_[j] = c + (lagged_[j] - c) * decay_half_[j];
        lagged_[j] = c + (lagged_[j] - c) * decay_[j];
      }
      apply(middle_);
      base_->advance(x0 + a * dx, v0 + a * dv, x0 + b * dx, v0 + b * dv, h, 1);
    }
    apply(lagged_);
  }
  [[nodiscard]] std::vector<double> states() const override {
    auto out = base_->states();
    out.insert(out.end(), lagged_.begin(), lagged_.end());
    return out;
  }
  void set_states(std::span<const double> states) override {
    const std::size_t own = states.size() - lagged_.size();
    base_->set_states(states.first(own));
    std::copy(states.begin() + static_cast<std::ptrdiff_t>(own), states.end(), lagged_.begin());
    apply(lagged_);
  }

 private:
  /// A factor of a law that reads a lagged variable: its coefficients' offset, and the lag it reads (or −1 and the
  /// variable's commanded value).
  struct Factor {
    const LawFactor* factor;
    int offset;
    int lag;
    double value;
  };
  struct LaggedLaw {
    int parameter;
    std::vector<Factor> factors;
  };

  /// The laws that read a lagged variable, each factor with what it reads: apply() evaluates only these, without
  /// a lookup by name (ParameterLaw::evaluate's arithmetic, factor by factor, so the same bits).
  void plan_lagged_laws() {
    plan_.clear();
    slots_.assign(lagged_.size(), nullptr);
    for (std::size_t i = 0; i < lagged_.size(); ++i) slots_[i] = &seen_[model_.lags()[i].variable];  // nodes stay put
    if (lagged_.empty()) return;
    const auto& laws = model_.laws();
    for (std::size_t j = 0; j < laws.size(); ++j) {
      if (laws[j].kind != ParameterLaw::Kind::product) continue;
      LaggedLaw law{static_cast<int>(j), {}};
      bool reads_lag = false;
      int offset = model_.coefficient_offset(static_cast<int>(j));
      for (const auto& f : laws[j].factors) {
        Factor entry{&f, offset, -1, std::nan("")};
        for (std::size_t i = 0; i < lagged_.size(); ++i)
          if (model_.lags()[i].variable == f.variable) entry.lag = static_cast<int>(i);
        if (entry.lag < 0)
          if (const auto it = commanded_.find(f.variable); it != commanded_.end()) entry.value = it->second;
        reads_lag = reads_lag || entry.lag >= 0;
        law.factors.push_back(entry);
        offset += f.size();
      }
      if (reads_lag) plan_.push_back(std::move(law));
    }
  }

  /// The base's parameters with each lagged variable at u[i] (the laws that read none keep their values); the
  /// variables too (seen_, the lagged ones at u) where the base reads them, or with `all`.
  void apply(const std::vector<double>& u, bool all = false) {
    if (coefficients_.empty()) return;
    if (plan_.empty() && !all) return;
    for (const auto& law : plan_) {
      double product = 1.0;
      for (const auto& f : law.factors)
        product *= f.factor->evaluate(coefficients_.data() + f.offset, f.lag >= 0 ? u[static_cast<std::size_t>(f.lag)] : f.value);
      base_values_[static_cast<std::size_t>(law.parameter)] = product;
    }
    if (model_.gauge_tied() >= 0) {  // LawModel::base_values' sum
      double sum = 0.0;
      for (int j : model_.gauge_sum_of()) sum += base_values_[static_cast<std::size_t>(j)];
      base_values_[static_cast<std::size_t>(model_.gauge_tied())] = sum;
    }
    if (all || base_->reads_variables()) {
      for (std::size_t i = 0; i < u.size(); ++i) *slots_[i] = u[i];
      base_->set_parameters(base_values_, seen_);
    } else {
      base_->set_parameter_values(base_values_);
    }
  }

  const LawModel& model_;
  std::unique_ptr<ModelStepper> base_;
  std::vector<double> coefficients_, base_values_;
  std::map<std::string, double> commanded_, seen_;  // the variables given, and with the lagged ones at u
  std::vector<double*> slots_;                      // seen_'s value of each lag
  std::vector<double> lagged_, tau_, commands_;  // u, τ and the commanded value of each lag
  std::vector<LaggedLaw> plan_;
  std::vector<double> middle_, decay_half_, decay_;  // advance's scratch: u at a sub-step's middle, e^(−h/2τ), e^(−h/τ)
};

}  // namespace

std::unique_ptr<ModelStepper> LawModel::stepper() const {
  auto base = base_.stepper();
  if (!base) return nullptr;
  return std::make_unique<LawStepper>(*this, std::move(base));
}

}  // namespace dampbench
