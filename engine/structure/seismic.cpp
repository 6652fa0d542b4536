#include "engine/structure/seismic.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/control/inverse.hpp"

namespace dampbench::structure {
namespace {

/// Secant iterations on r(F) = F − D(F) from the last step's force: the damper's force changes little over one
/// building step, and D depends on F only through the storey's motion (∂D/∂F ≈ c·dt/(2m) for a viscous c), so a
/// few iterations reach rounding. Returns the root; counts a step that did not get there in `unconverged`.
template <class DamperForce>
double solve_force(double start, DamperForce&& damper_force, int& unconverged) {
  constexpr int kIterations = 50;
  const auto tolerance = [](double F) { return 1e-9 + 1e-12 * std::fabs(F); };
  double Fa = start, ra = Fa - damper_force(Fa);
  if (std::fabs(ra) <= tolerance(Fa)) return Fa;
  double Fb = Fa - ra;
  for (int i = 0; i < kIterations; ++i) {
    const double rb = Fb - damper_force(Fb);
    if (std::fabs(rb) <= tolerance(Fb)) return Fb;
    if (!std::isfinite(rb) || rb == ra) break;
    const double Fc = Fb - rb * (Fb - Fa) / (rb - ra);
    Fa = Fb, ra = rb, Fb = Fc;
  }
  ++unconverged;
  return Fb;
}

/// The damper's stepper with its parameters and variables set; InputError naming what is missing.
std::unique_ptr<ModelStepper> damper_stepper(const Damper& damper, const std::optional<OnOffControl>& control) {
  if (!damper.model) throw InputError("structure: no damper model");
  if (damper.substeps < 1)
    throw InputError(fmt::format("--damper-substeps: expected a whole number >= 1, got {}", damper.substeps));
  auto stepper = damper.model->stepper();
  if (!stepper)
    throw InputError(fmt::format("structure: {} cannot be stepped sample by sample (a structure model or LS-SVM)",
                                 damper.model->id()));
  if (control) {
    control::check_commanded_variable(*damper.model, control->variable, "structure");
    if (!(control->low <= control->high))
      throw InputError(fmt::format("--command: expected low <= high, got {}:{}", control->low, control->high));
  }
  return stepper;
}

/// The building's matrices and Newmark's average-acceleration step for its time step: K_eff = K + (2/dt)·C +
/// (4/dt²)·M factored once, and g = K_eff⁻¹·e_d, the end-of-step displacements per newton of damper force.
struct NewmarkBuilding {
  NewmarkBuilding(const Building& b, double step_s)
      : dt(step_s), d(b.damper_storey - 1), m(b.mass_kg), M(b.mass_kg.asDiagonal()), K(b.stiffness_N_m),
        C(modes_of(b).damping_N_s_m), k_eff(K + (2.0 / dt) * C + (4.0 / (dt * dt)) * M),
        g(k_eff.solve(Eigen::VectorXd::Unit(b.storeys(), d))) {}

  /// The state at a step's end: u = u_free − g·F, with ü and u̇ from Newmark's rule.
  struct State {
    Eigen::VectorXd u, v, a;
  };
  /// u at the step's end under ground acceleration ag1 and no damper force.
  [[nodiscard]] Eigen::VectorXd free_end(const State& s, double ag1) const {
    return k_eff.solve(-m * ag1 + M * ((4.0 / (dt * dt)) * s.u + (4.0 / dt) * s.v + s.a) + C * ((2.0 / dt) * s.u + s.v));
  }
  [[nodiscard]] State end(const State& s, const Eigen::VectorXd& u1) const {
    const Eigen::VectorXd du = u1 - s.u;
    return {u1, (2.0 / dt) * du - s.v, (4.0 / (dt * dt)) * du - (4.0 / dt) * s.v - s.a};
  }
  /// The damper storey's (x, v, a) at the step's end for a damper force F.
  [[nodiscard]] std::array<double, 3> storey_end(const State& s, const Eigen::VectorXd& u_free, double F) const {
    const double dx = u_free[d] - g[d] * F - s.u[d];
    return {s.u[d] + dx, (2.0 / dt) * dx - s.v[d], (4.0 / (dt * dt)) * dx - (4.0 / dt) * s.v[d] - s.a[d]};
  }

  double dt;
  int d;
  Eigen::VectorXd m;  // M·1
  Eigen::MatrixXd M, K, C;
  Eigen::LLT<Eigen::MatrixXd> k_eff;
  Eigen::VectorXd g;
};

/// The damper inside the steps: its stepper, the variables it runs at and the command of the on/off rule.
class SteppedDamper {
 public:
  explicit SteppedDamper(const SeismicRun& run) : run_(run) {
    if (!run.damper) return;
    stepper_ = damper_stepper(*run.damper, run.control);
    variables_ = run.damper->variables;
    if (run.control) variables_[run.control->variable] = command_ = run.control->low;
    stepper_->set_parameters(run.damper->params, variables_);
    stepper_->reset();
  }
  [[nodiscard]] bool present() const { return stepper_ != nullptr; }
  [[nodiscard]] double command() const { return command_; }

  /// The force at rest under ground acceleration ag (x = v = 0; the storey's a = −ag − F/m_d).
  double at_rest(const NewmarkBuilding& nb, double ag, int& unconverged) {
    if (!stepper_) return 0.0;
    return solve_force(0.0, [&](double f) { return stepper_->force(0.0, 0.0, -ag - f / nb.m[nb.d]); }, unconverged);
  }
  /// The on/off rule's command from the state at a step's start and the damper's force F there.
  void choose_command(const NewmarkBuilding::State& s, double F) {
    if (!stepper_ || !run_.control) return;
    const OnOffControl& c = *run_.control;
    Eigen::VectorXd z(2 * s.u.size());
    z << s.u, s.v;
    const double desired = -c.gain.dot(z);
    const double next = desired * F > 0 && std::fabs(desired) > std::fabs(F) ? c.high : c.low;
    if (next == command_) return;
    command_ = variables_[c.variable] = next;
    stepper_->set_parameters(run_.damper->params, variables_);
  }
  /// The force at the step's end that the building's motion and the damper agree on, with the damper's states
  /// left at it.
  double end_force(const NewmarkBuilding& nb, const NewmarkBuilding::State& s, const Eigen::VectorXd& u_free, double F,
                   int& unconverged) {
    if (!stepper_) return 0.0;
    const std::vector<double> saved = stepper_->states();
    const auto force_at = [&](double f) {
      const auto [x, v, a] = nb.storey_end(s, u_free, f);
      stepper_->set_states(saved);
      stepper_->advance(s.u[nb.d], s.v[nb.d], x, v, nb.dt, run_.damper->substeps);
      return stepper_->force(x, v, a);
    };
    const double F1 = solve_force(F, force_at, unconverged);
    (void)force_at(F1);
    return F1;
  }

 private:
  const SeismicRun& run_;
  std::unique_ptr<ModelStepper> stepper_;
  std::map<std::string, double> variables_;
  double command_ = std::nan("");
};

void check_run(const SeismicRun& run) {
  check_building(run.building, run.building.name);
  if (!(run.step_s > 0) || !std::isfinite(run.step_s))
    throw InputError(fmt::format("--step: expected a time step > 0 s, got {}", run.step_s));
  if (run.output_every < 1) throw InputError(fmt::format("output every: expected >= 1 step, got {}", run.output_every));
  if (run.ground.t_s.size() < 2) throw InputError("structure: the ground motion has fewer than two samples");
}

/// The time histories' rows and the peaks.
struct Recorder {
  Recorder(SeismicResponse& response, int storeys, std::size_t rows) : r(response), n(storeys) {
    r.u_m.setZero(static_cast<Eigen::Index>(rows), n);
    r.drift_m = r.abs_acc_m_s2 = r.u_m;
    r.peak_u_m = r.peak_drift_m = r.peak_abs_acc_m_s2 = Eigen::VectorXd::Zero(n);
  }
  void peaks(const NewmarkBuilding::State& s, double ag, double F) const {
    for (int i = 0; i < n; ++i) {
      r.peak_u_m[i] = std::max(r.peak_u_m[i], std::fabs(s.u[i]));
      r.peak_drift_m[i] = std::max(r.peak_drift_m[i], std::fabs(s.u[i] - (i > 0 ? s.u[i - 1] : 0.0)));
      r.peak_abs_acc_m_s2[i] = std::max(r.peak_abs_acc_m_s2[i], std::fabs(s.a[i] + ag));
    }
    r.peak_force_N = std::max(r.peak_force_N, std::fabs(F));
  }
  void row(std::size_t k, double t, const NewmarkBuilding::State& s, double ag, double F, double command) const {
    const auto i = static_cast<Eigen::Index>(k);
    r.t_s.push_back(t);
    r.ag_m_s2.push_back(ag);
    r.force_N.push_back(F);
    r.command.push_back(command);
    r.u_m.row(i) = s.u.transpose();
    for (int j = 0; j < n; ++j) {
      r.drift_m(i, j) = s.u[j] - (j > 0 ? s.u[j - 1] : 0.0);
      r.abs_acc_m_s2(i, j) = s.a[j] + ag;
    }
  }
  SeismicResponse& r;
  int n;
};

}  // namespace

SeismicResponse simulate_seismic(const SeismicRun& run) {
  check_run(run);
  const NewmarkBuilding nb(run.building, run.step_s);
  SteppedDamper damper(run);
  const int n = run.building.storeys();
  const double dt = run.step_s, t0 = run.ground.t_s.front();
  const auto steps = static_cast<std::size_t>(std::floor(run.ground.duration_s() / dt + 1e-9));
  const auto every = static_cast<std::size_t>(run.output_every);
  SeismicResponse r;
  const Recorder recorder(r, n, steps / every + 1);
  // At rest: the damper's force at x = v = 0 (a law may have a static part, Spencer's k1·(0 − x0)) and the
  // accelerations of the equation of motion under it.
  double ag = run.ground.at(t0);
  double F = damper.at_rest(nb, ag, r.unconverged_steps);
  NewmarkBuilding::State s{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), -Eigen::VectorXd::Ones(n) * ag};
  s.a[nb.d] -= F / nb.m[nb.d];
  double max_input = 0;
  std::size_t high_steps = 0;
  recorder.row(0, t0, s, ag, F, damper.command());
  for (std::size_t step = 0; step < steps; ++step) {
    const double t1 = t0 + static_cast<double>(step + 1) * dt, ag1 = run.ground.at(t1);
    damper.choose_command(s, F);
    high_steps += run.control && damper.command() == run.control->high;
    const Eigen::VectorXd u_free = nb.free_end(s, ag1);
    const double F1 = damper.end_force(nb, s, u_free, F, r.unconverged_steps);
    const NewmarkBuilding::State s1 = nb.end(s, u_free - nb.g * F1);
    const Eigen::VectorXd du = s1.u - s.u;
    r.energy.input_J -= du.dot(nb.m) * 0.5 * (ag + ag1);
    r.energy.structural_J += du.dot(nb.C * (0.5 * (s.v + s1.v)));
    r.energy.damper_J += du[nb.d] * 0.5 * (F + F1);
    max_input = std::max(max_input, std::fabs(r.energy.input_J));
    s = s1, F = F1, ag = ag1;
    recorder.peaks(s, ag, F);
    if ((step + 1) % every == 0) recorder.row((step + 1) / every, t1, s, ag, F, damper.command());
  }
  r.steps = static_cast<int>(steps);
  r.high_share = steps > 0 && run.control ? static_cast<double>(high_steps) / static_cast<double>(steps) : 0.0;
  r.energy.kinetic_J = 0.5 * s.v.dot(nb.M * s.v);
  r.energy.strain_J = 0.5 * s.u.dot(nb.K * s.u);
  const Energies& e = r.energy;
  r.energy.balance_error = max_input > 0 ? std::fabs(e.input_J - (e.structural_J + e.damper_J + e.kinetic_J + e.strain_J)) / max_input : 0.0;
  return r;
}

}  // namespace dampbench::structure
