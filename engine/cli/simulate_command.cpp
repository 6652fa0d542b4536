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
#include "engine/fit/model_file.hpp"
#include "engine/fit/resolve_model.hpp"
#include "engine/record/excitation.hpp"
#include "engine/record/record_options.hpp"

namespace dampbench::cli {

void add_simulate_options(CLI::App* c, SimulateOptions& sim) {
  c->add_option("--model", sim.model, "model id (see `dampbench models`)");
  c->add_option("--fixture", sim.fixture, "published law fixture instead of --model, e.g. mfm.table3");
  c->add_option("--laws", sim.laws, "parameter laws, e.g. 'c0=poly(I,1);alpha=poly(I,1)'");
  c->add_option("--params", sim.params, "parameter (or law coefficient) values in SI, name=value,...");
  c->add_option("--model-file", sim.model_file, "a fitted model (fit --save-model) instead of --model/--fixture, --laws, --params");
  c->add_option("--input", sim.input.path, "displacement record (CSV); t and x are used");
  add_data_options(c, sim.input);
  c->add_option("--sine", sim.sine, "sinusoid: amp=m,freq=Hz (or vpeak=m/s),cycles=N,fs=Hz");
  c->add_option("--noise-rel", sim.noise_rel, "Gaussian noise, std = R x RMS(force)");
  c->add_option("--seed", sim.seed, "noise seed");
  c->add_option("-o,--output", sim.output, "output CSV (t,x,v,a,F in SI; t,y,u for a system record); default stdout");
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

/// The model and its parameters from --model-file, or from --model/--fixture, --laws and --params.
LoadedModel simulated_model(const SimulateOptions& o) {
  LoadedModel m;
  if (!o.model_file.empty()) {
    if (!o.model.empty() || !o.fixture.empty() || !o.laws.empty() || !o.params.empty())
      throw InputError("simulate: --model-file gives the model, its laws and coefficients: drop --model, --fixture, "
                       "--laws and --params");
    return load_model_file(o.model_file);
  }
  if (o.model.empty() == o.fixture.empty())
    throw InputError("simulate: give exactly one of --model M or --fixture NAME (or --model-file FILE)");
  // A fixture is a law model already: --laws applies to --model only.
  m.model = resolve_model(o.fixture.empty() ? command_line_model(o.model, o.laws)
                                            : command_line_model("", "", "", o.fixture));
  m.params = parse_params(*m.model.model, o.params, m.model.defaults);
  return m;
}

}  // namespace

Simulation run_simulate(const SimulateOptions& o) {
  const int displacements = !o.sine.empty() + !o.input.path.empty() + o.record.has_value();
  if (displacements != 1)
    throw InputError("simulate: give exactly one of --input FILE or --sine amp=...,freq=...,cycles=...,fs=...");
  if (!(o.noise_rel >= 0) || !std::isfinite(o.noise_rel))
    throw InputError(fmt::format("--noise-rel: expected a number >= 0, got {}", o.noise_rel));
  const LoadedModel loaded = simulated_model(o);
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
  sim.force = model.simulate(loaded.params, signals);
  sim.response = structure_response(model, loaded.params, signals);
  if (o.noise_rel > 0) add_noise(sim.force, o.noise_rel, o.seed);
  return sim;
}

int simulate_command(const SimulateOptions& o) {
  const Simulation sim = run_simulate(o);
  if (!sim.extrapolated.empty())
    std::cerr << fmt::format("note: outside the range {} was fitted on: {}\n", o.model_file, sim.extrapolated);
  const Dataset& data = sim.data;
  std::ofstream file;
  if (!o.output.empty()) {
    file.open(o.output);
    if (!file) throw StoreError(fmt::format("-o: cannot write '{}'", o.output));
  }
  std::ostream& out = o.output.empty() ? std::cout : file;
  if (data.is_system()) {  // a structure model: its displacement y (with any noise), the input u, and its states
    const bool states = o.states && sim.response;
    out << (states ? "t,y,u,v,a,z\n" : "t,y,u\n");
    for (std::size_t k = 0; k < sim.force.size(); ++k) {
      out << fmt::format("{:.17g},{:.17g},{:.17g}", data.t_s[k], sim.force[k], data.u_N[k]);
      if (states)
        out << fmt::format(",{:.17g},{:.17g},{:.17g}", sim.response->v_m_s[k], sim.response->a_m_s2[k],
                           sim.response->z_N[k]);
      out << "\n";
    }
    return 0;
  }
  out << "t,x,v,a,F\n";
  for (std::size_t k = 0; k < sim.force.size(); ++k)
    out << fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", data.t_s[k], data.x_m[k], data.v_m_s[k],
                       data.a_m_s2[k], sim.force[k]);
  return 0;
}

}  // namespace dampbench::cli
