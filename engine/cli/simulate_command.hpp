#pragma once
// `dampbench simulate`: the force of a model with given parameters under a displacement (a record or a sine),
// optionally with Gaussian noise, as CSV.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/record/record_options.hpp"
#include "models/structure.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

struct SimulateOptions {
  std::string model;
  std::string fixture;  ///< a published law fixture instead of --model (models/fixtures.hpp)
  std::string laws;     ///< "c0=poly(I,1);..." laws on the model's parameters
  std::string params;   ///< "name=value,..." in SI (the fixture's values by default)
  std::string model_file;  ///< a model file (fit --save-model) instead of model, fixture, laws and params
  RecordOptions input;   ///< used when sine is empty and no record is given
  std::optional<Dataset> record;  ///< a record already loaded, instead of input.path or sine (the Python module's)
  std::string sine;    ///< "amp=...,freq=...,cycles=...,fs=..."
  double noise_rel = 0;
  std::uint64_t seed = 1;
  std::string output;  ///< CSV path; stdout when empty
  bool states = false;
  /// RK4 sub-steps per sample interval, fixed: the model stepped sample by sample (engine/model/stepper.hpp),
  /// the scheme `export` builds in; 0 runs the batch kernel, whose sub-steps follow the record.
  int fixed_step = 0;  ///< a structure model: also write ẏ, ÿ and z (the file is then no longer a record to load)
};

/// A displacement and the model's force under it, as `dampbench simulate` prints them.
struct Simulation {
  Dataset data;               ///< t, x, v, a (SI) of the record or sine; t, u of a system record
  std::vector<double> force;  ///< F [N], with the noise asked for; a structure model's displacement y [m]
  std::optional<StructureResponse> response;  ///< a structure model's y (without noise), ẏ, ÿ and z
  /// With --model-file: the record's law variables outside the range the model was fitted on ("" inside).
  std::string extrapolated = {};
};

void add_simulate_options(CLI::App* cmd, SimulateOptions& options);

/// Checks the options, builds the model and the displacement, and simulates (the Python module's simulate too).
Simulation run_simulate(const SimulateOptions& options);

int simulate_command(const SimulateOptions& options);

}  // namespace dampbench::cli
