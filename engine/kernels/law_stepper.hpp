#pragma once
// A kernel law stepped one sample at a time (engine/model/stepper.hpp): the same Law structs the lane kernels
// run, in one lane (W = 1), so a stepped model and the batch kernels share their equations. ODE laws step by
// RK4 in the sub-steps the caller gives, with |s|^e taken exactly at every stage (the batch kernel's series is a
// speed-up of the same power); algebraic laws evaluate at the sample.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "engine/kernels/lane_kernel.hpp"
#include "engine/kernels/substep_rule.hpp"
#include "engine/model/stepper.hpp"

namespace dampbench {

/// A one-sample view of a record for the laws' per-sample and per-record quantities: the inputs (x, v, a) with
/// the invariants prepare_signals computes, and the operating variables (the fdsp laws read V, and w when given).
class SampleSignals {
 public:
  SampleSignals() {
    for (auto* column : {&s_.t_s, &s_.x_m, &s_.v_m_s, &s_.a_m_s2, &s_.sgn_x, &s_.sgn_v, &s_.log_abs_x, &s_.log_abs_v})
      column->assign(1, 0.0);
  }
  void set_variables(const std::map<std::string, double>& variables) {
    assign(s_.operating, variables);
    assign(s_.law_variables, variables);
    const auto w = variables.find("w");
    const auto freq = variables.find("freq");
    s_.excitation_freq_hz = w != variables.end() ? w->second : freq != variables.end() ? freq->second : 0.0;
  }
  const Signals& at(double x, double v, double a) {
    s_.x_m[0] = x, s_.v_m_s[0] = v, s_.a_m_s2[0] = a;
    s_.sgn_x[0] = sign(x), s_.sgn_v[0] = sign(v);
    s_.log_abs_x[0] = log_abs_clamped(x), s_.log_abs_v[0] = log_abs_clamped(v);
    return s_;
  }
  [[nodiscard]] const Signals& signals() const { return s_; }

 private:
  /// to = from, in place when they hold the same names: a lagged law model sets its base's parameters and
  /// variables at every sub-step, and a map's copy was most of such a step's time.
  static void assign(std::map<std::string, double>& to, const std::map<std::string, double>& from) {
    if (to.size() == from.size() &&
        std::equal(to.begin(), to.end(), from.begin(), [](const auto& a, const auto& b) { return a.first == b.first; })) {
      auto it = to.begin();
      for (const auto& [name, value] : from) (it++)->second = value;
    } else {
      to = from;
    }
  }
  Signals s_;
};

/// Lanes of one candidate from the model's parameters (logic_error on a wrong count: the Model checks names).
template <class Law>
LawLanes<Law, 1> stepper_lanes(std::span<const double> params) {
  if (params.size() != static_cast<std::size_t>(Law::kParams))
    throw std::logic_error("stepper: " + Law::info().id + " takes " + std::to_string(Law::kParams) + " parameters");
  return broadcast_lanes<Law, 1>(params);
}

/// An algebraic law: the force at the sample; no states.
template <class Law>
class AlgebraicLawStepper final : public ModelStepper {
 public:
  void set_parameters(std::span<const double> params, const std::map<std::string, double>& variables) override {
    p_ = stepper_lanes<Law>(params);
    sample_.set_variables(variables);
  }
  void set_parameter_values(std::span<const double> params) override { p_ = stepper_lanes<Law>(params); }
  void reset() override {}
  [[nodiscard]] double force(double x, double v, double a) const override {
    const Signals& s = sample_.at(x, v, a);
    if constexpr (requires { Law::template prepare<double>(s, 0); }) return force_of(Law::template prepare<double>(s, 0));
    else return force_of(Law::prepare(s, 0));
  }
  void advance(double, double, double, double, double, int) override {}
  [[nodiscard]] std::vector<double> states() const override { return {}; }
  void set_states(std::span<const double>) override {}

 private:
  template <class Sample>
  double force_of(const Sample& s) const {
    if constexpr (requires { Law::exp_argument(p_, 0, s); }) return Law::force_with_exp(p_, 0, s, std::exp(Law::exp_argument(p_, 0, s)));
    else return Law::force(p_, 0, s);
  }
  LawLanes<Law, 1> p_{};
  mutable SampleSignals sample_;
};

/// An ODE law: RK4 in fixed sub-steps, inputs linear over the interval (the batch kernel's arithmetic for them).
template <class Law>
class OdeLawStepper final : public ModelStepper {
  static constexpr int S = Law::kStates;
  static constexpr bool kPower = requires { Law::kPowerState; };

 public:
  void set_parameters(std::span<const double> params, const std::map<std::string, double>& variables) override {
    p_ = stepper_lanes<Law>(params);
    sample_.set_variables(variables);
    ctx_ = Law::context(sample_.signals());
  }
  void set_parameter_values(std::span<const double> params) override { p_ = stepper_lanes<Law>(params); }
  /// Only a law with a per-record context (fdsp's V and ω) reads the variables.
  [[nodiscard]] bool reads_variables() const override { return !std::is_empty_v<typename Law::Context>; }
  void reset() override { y_.fill(0.0); }
  [[nodiscard]] double force(double x, double v, double) const override { return Law::force(p_, 0, ctx_, x, v, y_.data()); }
  void advance(double x0, double v0, double x1, double v1, double dt, int substeps) override {
    const double inv = 1.0 / substeps, h = dt * inv, dx = x1 - x0, dv = v1 - v0;
    std::array<double, S> t{}, k1{}, k2{}, k3{}, k4{};
    for (int i = 0; i < substeps; ++i) {
      const double a = i * inv, m = (i + 0.5) * inv, b = (i + 1) * inv;
      rhs(x0 + a * dx, v0 + a * dv, y_.data(), k1.data());
      for (int j = 0; j < S; ++j) t[j] = y_[j] + 0.5 * h * k1[j];
      rhs(x0 + m * dx, v0 + m * dv, t.data(), k2.data());
      for (int j = 0; j < S; ++j) t[j] = y_[j] + 0.5 * h * k2[j];
      rhs(x0 + m * dx, v0 + m * dv, t.data(), k3.data());
      for (int j = 0; j < S; ++j) t[j] = y_[j] + h * k3[j];
      rhs(x0 + b * dx, v0 + b * dv, t.data(), k4.data());
      for (int j = 0; j < S; ++j) y_[j] += (h / 6.0) * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
    }
  }
  [[nodiscard]] double stiffness(double velocity_max_abs_m_s, double displacement_ptp_m) const override {
    if constexpr (requires { Law::stiffness(p_, 0, ctx_, RecordScales{}); }) {
      const double estimate = Law::stiffness(p_, 0, ctx_, RecordScales{velocity_max_abs_m_s, displacement_ptp_m});
      return std::isfinite(estimate) ? std::max(estimate, 0.0) : std::numeric_limits<double>::infinity();
    } else {
      return 0;
    }
  }
  [[nodiscard]] int kernel_substeps(const Signals& data, std::size_t k, double lambda) const override {
    const int n = ode_substeps(data, k, Law::kSubstepsPerStroke, law_stroke_driven<Law>());
    const double stiff = std::ceil((data.t_s[k] - data.t_s[k - 1]) * lambda / law_stiff_step<Law>());
    if (!(stiff <= kMaxSubsteps)) return 0;  // masked as too stiff (+inf λ included)
    return std::max(n, static_cast<int>(stiff));
  }
  [[nodiscard]] std::vector<double> states() const override { return {y_.begin(), y_.end()}; }
  void set_states(std::span<const double> states) override {
    if (states.size() != static_cast<std::size_t>(S)) throw std::logic_error("stepper: wrong number of states");
    std::copy(states.begin(), states.end(), y_.begin());
  }

 private:
  void rhs(double x, double v, const double* y, double* dy) const {
    if constexpr (kPower)
      Law::rhs(p_, 0, ctx_, x, v, y, abs_pow(y[Law::kPowerState], p_.p[Law::kPowerExponentRow][0]), dy);
    else
      Law::rhs(p_, 0, ctx_, x, v, y, dy);
  }
  LawLanes<Law, 1> p_{};
  SampleSignals sample_;  // kept: a lagged law model sets the parameters at every sub-step
  typename Law::Context ctx_{};
  std::array<double, S> y_{};
};

}  // namespace dampbench
