#include "engine/cli/simulate_command.hpp"

#include <cmath>
#include <fstream>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "engine/cli/cli_options.hpp"
#include "engine/common/error.hpp"
#include "engine/common/random.hpp"
#include "engine/fit/fit.hpp"
#include "engine/model/stepped_simulation.hpp"
#include "engine/fit/lssvm_model_file.hpp"
#include "engine/fit/model_file.hpp"
#include "engine/fit/resolve_model.hpp"
#include "engine/record/excitation.hpp"
#include "engine/record/mat_file.hpp"
#include "engine/record/record_options.hpp"

namespace dampbench::cli {

void add_simulate_options(CLI::App* c, SimulateOptions& sim) {
  c->add_option("--model", sim.model, "model id (see `dampbench models`)");
  c->add_option("--fixture", sim.fixture, "published law fixture instead of --model, e.g. mfm.table3");
  c->add_option("--laws", sim.laws, "parameter laws, e.g. 'c0=poly(I,1);alpha=poly(I,1)'");
  c->add_option("--params", sim.params, "parameter (or law coefficient) values in SI, name=value,...");
  c->add_option("--model-file", sim.model_file,
                "a fitted model (fit --save-model, or lssvm --save-model: its free run from --input's first forces) "
                "instead of --model/--fixture, --laws, --params");
  c->add_option("--input", sim.input.path, "displacement record (CSV); t and x are used");
  add_data_options(c, sim.input);
  c->add_option("--sine", sim.sine, "sinusoid: amp=m,freq=Hz (or vpeak=m/s),cycles=N,fs=Hz");
  c->add_option("--noise-rel", sim.noise_rel, "Gaussian noise, std = R x RMS(force)");
  c->add_option("--seed", sim.seed, "noise seed");
  c->add_option("-o,--output", sim.output, "output CSV (t,x,v,a,F in SI; t,y,u for a system record), or a MATLAB file (.mat: one variable per column); default stdout");
  c->add_option("--fixed-step", sim.fixed_step,
                "N: step the model sample by sample with N fixed RK4 sub-steps per interval (the scheme of a "
                "controller, a structure and the C export); default: the batch kernel's sub-steps, which follow the record");
  c->add_flag("--states", sim.states, "a structure model (sys.*): also write its velocity v, acceleration a and hysteretic force z");
}

namespace {

/// Adds Gaussian noise of std noise_rel × RMS of the force, from the seed's own stream.
void add_noise(std::vector<double>& force, double noise_rel, std::uint64_t seed) {
  double sum_sq = 0;
  for (double f : force) sum_sq += f * f;
  const double noise_std = noise_rel * std::sqrt(sum_sq / static_cast<double>(force.size()));
  RandomStream rng(hash_key({seed, hash_name("simulate-noise")}));
  for (double& f : force) f += noise_std * rng.normal();
}

/// An LS-SVM model file (lssvm --save-model): its free run on a record whose first lag samples give the measured
/// forces it starts from (engine/fit/lssvm_model_file.hpp).
Simulation simulate_lssvm(const SimulateOptions& o) {
  if (!o.model.empty() || !o.fixture.empty() || !o.laws.empty() || !o.params.empty())
    throw InputError("simulate: --model-file gives the model: drop --model, --fixture, --laws and --params");
  if (!o.sine.empty())
    throw InputError("simulate: an LS-SVM model runs from a record's first measured forces: give --input FILE with a "
                     "force column, not --sine");
  const lssvm::Model model = load_lssvm_model_file(o.model_file);
  Simulation sim;
  sim.data = o.record ? *o.record : load_record(o.input, true);
  if (o.input.path.empty() && !o.input.set.empty()) set_operating(sim.data, o.input.set);
  sim.force = model.simulate(sim.data);
  if (o.noise_rel > 0) add_noise(sim.force, o.noise_rel, o.seed);
  return sim;
}

}  // namespace

Simulation run_simulate(const SimulateOptions& o) {
  const int displacements = !o.sine.empty() + !o.input.path.empty() + o.record.has_value();
  if (displacements != 1)
    throw InputError("simulate: give exactly one of --input FILE or --sine amp=...,freq=...,cycles=...,fs=...");
  if (!(o.noise_rel >= 0) || !std::isfinite(o.noise_rel))
    throw InputError(fmt::format("--noise-rel: expected a number >= 0, got {}", o.noise_rel));
  if (!o.model_file.empty() && is_lssvm_model_file(o.model_file)) return simulate_lssvm(o);
  const LoadedModel loaded = load_named_model({o.model_file, o.model, o.fixture, o.laws, o.params}, "simulate");
  const Model& model = *loaded.model.model;
  Simulation sim;
  if (o.record) sim.data = *o.record;
  else if (o.sine.empty()) sim.data = load_record(o.input, false);
  else sim.data = make_sine(parse_sine_option(o.sine));
  // A file's loader applies --set itself; a sine or a given record take it here.
  if (o.input.path.empty() && !o.input.set.empty()) set_operating(sim.data, o.input.set);
  const Signals signals = prepare_signals(sim.data);
  check_record(model, signals);
  if (!o.model_file.empty()) sim.extrapolated = fitted_range_of(loaded).outside(signals.law_variables);
  if (o.fixed_step < 0)
    throw InputError(fmt::format("--fixed-step: expected a whole number of sub-steps >= 1, got {}", o.fixed_step));
  sim.force = o.fixed_step > 0 ? simulate_stepped(model, loaded.params, signals, o.fixed_step)
                               : model.simulate(loaded.params, signals);
  sim.response = structure_response(model, loaded.params, signals);
  if (o.noise_rel > 0) add_noise(sim.force, o.noise_rel, o.seed);
  return sim;
}

namespace {

/// The simulated record's columns in SI: t,y,u (and v,a,z with --states) of a structure, t,x,v,a,F of a rig (and
/// its varying I, V or phi).
std::vector<std::pair<std::string, std::vector<double>>> simulated_columns(const Simulation& sim, bool states) {
  const Dataset& data = sim.data;
  if (data.is_system()) {  // a structure model: its displacement y (with any noise), the input u, and its states
    std::vector<std::pair<std::string, std::vector<double>>> c{{"t", data.t_s}, {"y", sim.force}, {"u", data.u_N}};
    if (states && sim.response) {
      c.emplace_back("v", sim.response->v_m_s);
      c.emplace_back("a", sim.response->a_m_s2);
      c.emplace_back("z", sim.response->z_N);
    }
    return c;
  }
  std::vector<std::pair<std::string, std::vector<double>>> c{
      {"t", data.t_s}, {"x", data.x_m}, {"v", data.v_m_s}, {"a", data.a_m_s2}, {"F", sim.force}};
  // A command that varies over the test (I, V or phi) goes with the forces it made, so that `fit` reads it back.
  for (const auto& [name, column] : data.operating_signals) c.emplace_back(name, column);
  return c;
}

}  // namespace

int simulate_command(const SimulateOptions& o) {
  const Simulation sim = run_simulate(o);
  if (!sim.extrapolated.empty())
    std::cerr << fmt::format("note: outside the range {} was fitted on: {}\n", o.model_file, sim.extrapolated);
  const auto columns = simulated_columns(sim, o.states);
  if (is_mat_path(o.output)) {  // one N x 1 variable per column, read back by --data FILE.mat
    write_mat_file(o.output, columns);
    return 0;
  }
  std::ofstream file;
  if (!o.output.empty()) {
    file.open(o.output);
    if (!file) throw StoreError(fmt::format("-o: cannot write '{}'", o.output));
  }
  std::ostream& out = o.output.empty() ? std::cout : file;
  for (std::size_t j = 0; j < columns.size(); ++j) out << (j ? "," : "") << columns[j].first;
  out << "\n";
  for (std::size_t k = 0; k < columns.front().second.size(); ++k) {
    for (std::size_t j = 0; j < columns.size(); ++j) out << (j ? "," : "") << fmt::format("{:.17g}", columns[j].second[k]);
    out << "\n";
  }
  return 0;
}

}  // namespace dampbench::cli
