#include "engine/structure/seismic.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/model/law_model.hpp"

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
    const auto* laws = dynamic_cast<const LawModel*>(damper.model);
    const auto names = laws ? laws->law_variables() : std::vector<std::string>{};
    if (std::find(names.begin(), names.end(), control.value().variable) == names.end())
      throw InputError(fmt::format("structure: the damper model {} has no law in {}, the commanded variable: fit it with "
                                   "laws in {} (fit --laws \"...=poly({},1)\")",
                                   damper.model->id(), control->variable, control->variable, control->variable));
    if (!(control->low <= control->high))
      throw InputError(fmt::format("--command: expected low <= high, got {}:{}", control->low, control->high));
  }
  return stepper;
}

}  // namespace

SeismicResponse simulate_seismic(const SeismicRun& run) {
  const Building& b = run.building;
  check_building(b, b.name);
  if (!(run.step_s > 0) || !std::isfinite(run.step_s))
    throw InputError(fmt::format("--step: expected a time step > 0 s, got {}", run.step_s));
  if (run.output_every < 1) throw InputError(fmt::format("output every: expected >= 1 step, got {}", run.output_every));
  if (run.ground.t_s.size() < 2) throw InputError("structure: the ground motion has fewer than two samples");
  const int n = b.storeys(), d = b.damper_storey - 1;
  const double dt = run.step_s;
  const Modes modes = modes_of(b);
  const Eigen::VectorXd& m = b.mass_kg;
  const Eigen::MatrixXd M = m.asDiagonal();
  const Eigen::MatrixXd& K = b.stiffness_N_m;
  const Eigen::MatrixXd& C = modes.damping_N_s_m;
  const Eigen::LLT<Eigen::MatrixXd> k_eff(K + (2.0 / dt) * C + (4.0 / (dt * dt)) * M);
  const Eigen::VectorXd g = k_eff.solve(Eigen::VectorXd::Unit(n, d));  // u's response to a unit damper force

  std::unique_ptr<ModelStepper> damper;
  std::map<std::string, double> variables;
  if (run.damper) {
    damper = damper_stepper(*run.damper, run.control);
    variables = run.damper->variables;
    if (run.control) variables[run.control->variable] = run.control->low;
    damper->set_parameters(run.damper->params, variables);
    damper->reset();
  }
  double command = run.control ? run.control->low : std::nan("");

  SeismicResponse r;
  const std::size_t steps = static_cast<std::size_t>(std::floor(run.ground.duration_s() / dt + 1e-9));
  const std::size_t rows = steps / static_cast<std::size_t>(run.output_every) + 1;
  r.u_m.setZero(static_cast<Eigen::Index>(rows), n);
  r.drift_m = r.abs_acc_m_s2 = r.u_m;
  r.peak_u_m = r.peak_drift_m = r.peak_abs_acc_m_s2 = Eigen::VectorXd::Zero(n);

  Eigen::VectorXd u = Eigen::VectorXd::Zero(n), v = u, a = u;
  const double t0 = run.ground.t_s.front();
  double ag = run.ground.at(t0);
  // At rest: the damper's force at x = v = 0 (a law may have a static part, Spencer's k1·(0 − x0)), with the
  // storey's acceleration a = −ag − F/m_d of the equation of motion (fvd's m·a term).
  double F = 0;
  if (damper) F = solve_force(0.0, [&](double f) { return damper->force(0.0, 0.0, -ag - f / m[d]); }, r.unconverged_steps);
  a = -Eigen::VectorXd::Ones(n) * ag;
  a[d] -= F / m[d];
  const Eigen::VectorXd m_ones = m;  // M·1
  double max_input = 0;
  std::size_t high_steps = 0;

  const auto record = [&](std::size_t row, double t) {
    const auto i = static_cast<Eigen::Index>(row);
    r.t_s.push_back(t);
    r.ag_m_s2.push_back(ag);
    r.force_N.push_back(F);
    r.command.push_back(command);
    r.u_m.row(i) = u.transpose();
    for (int s = 0; s < n; ++s) {
      r.drift_m(i, s) = u[s] - (s > 0 ? u[s - 1] : 0.0);
      r.abs_acc_m_s2(i, s) = a[s] + ag;
    }
  };
  record(0, t0);
  for (std::size_t step = 0; step < steps; ++step) {
    const double t1 = t0 + static_cast<double>(step + 1) * dt, ag1 = run.ground.at(t1);
    if (damper && run.control) {  // the command for this step, from the state at its start
      Eigen::VectorXd z(2 * n);
      z << u, v;
      const double desired = -run.control->gain.dot(z);
      const double next = desired * F > 0 && std::fabs(desired) > std::fabs(F) ? run.control->high : run.control->low;
      if (next != command) {
        command = variables[run.control->variable] = next;
        damper->set_parameters(run.damper->params, variables);
      }
      high_steps += command == run.control->high;
    }
    const Eigen::VectorXd rhs = -m_ones * ag1 + M * ((4.0 / (dt * dt)) * u + (4.0 / dt) * v + a) + C * ((2.0 / dt) * u + v);
    const Eigen::VectorXd u_free = k_eff.solve(rhs);  // u at the step's end without the damper's force
    double F1 = 0;
    if (damper) {
      const std::vector<double> saved = damper->states();
      const auto force_at = [&](double f) {
        const double x = u_free[d] - g[d] * f, dx = x - u[d];
        const double vx = (2.0 / dt) * dx - v[d], ax = (4.0 / (dt * dt)) * dx - (4.0 / dt) * v[d] - a[d];
        damper->set_states(saved);
        damper->advance(u[d], v[d], x, vx, dt, run.damper->substeps);
        return damper->force(x, vx, ax);
      };
      F1 = solve_force(F, force_at, r.unconverged_steps);
      (void)force_at(F1);  // the damper's states at the force the building takes
    }
    const Eigen::VectorXd u1 = u_free - g * F1, du = u1 - u;
    const Eigen::VectorXd v1 = (2.0 / dt) * du - v;
    const Eigen::VectorXd a1 = (4.0 / (dt * dt)) * du - (4.0 / dt) * v - a;
    r.energy.input_J -= du.dot(m_ones) * 0.5 * (ag + ag1);
    r.energy.structural_J += du.dot(C * (0.5 * (v + v1)));
    r.energy.damper_J += du[d] * 0.5 * (F + F1);
    max_input = std::max(max_input, std::fabs(r.energy.input_J));
    u = u1, v = v1, a = a1, F = F1, ag = ag1;
    for (int s = 0; s < n; ++s) {
      r.peak_u_m[s] = std::max(r.peak_u_m[s], std::fabs(u[s]));
      r.peak_drift_m[s] = std::max(r.peak_drift_m[s], std::fabs(u[s] - (s > 0 ? u[s - 1] : 0.0)));
      r.peak_abs_acc_m_s2[s] = std::max(r.peak_abs_acc_m_s2[s], std::fabs(a[s] + ag));
    }
    r.peak_force_N = std::max(r.peak_force_N, std::fabs(F));
    if ((step + 1) % static_cast<std::size_t>(run.output_every) == 0) record((step + 1) / run.output_every, t1);
  }
  r.steps = static_cast<int>(steps);
  r.high_share = steps > 0 && run.control ? static_cast<double>(high_steps) / static_cast<double>(steps) : 0.0;
  r.energy.kinetic_J = 0.5 * v.dot(M * v);
  r.energy.strain_J = 0.5 * u.dot(K * u);
  const Energies& e = r.energy;
  const double out = e.structural_J + e.damper_J + e.kinetic_J + e.strain_J;
  r.energy.balance_error = max_input > 0 ? std::fabs(e.input_J - out) / max_input : 0.0;
  return r;
}

}  // namespace dampbench::structure
