#pragma once
// `dampbench structure`: an identified damper inside a building under an earthquake (engine/structure): the
// building bare and with the damper, passive at the record's operating variables or semi-active by the on/off
// rule of an LQR gain; peaks, their reductions, the energy balance and the time histories.
#include <string>

#include "engine/cli/cli_options.hpp"
#include "engine/structure/seismic.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

struct StructureOptions {
  ModelByName damper;            ///< --model-file, or --model/--fixture with --laws and --params
  std::string building;          ///< a building TOML file (datasets/buildings/*.toml)
  std::string ground;            ///< a ground-acceleration CSV (t, ag)
  double scale = 1.0;            ///< factor on ag
  double step_s = 1.0 / 4096.0;  ///< the building's time step
  int damper_substeps = 4;
  std::string set;               ///< the damper's operating variables, "I=1,..."
  std::string control = "passive";  ///< passive or on-off
  std::string command;           ///< "I=0:1": the commanded variable and its range (on-off)
  double lqr_r = 1e-6;           ///< R of the LQR cost ∫ zᵀQz + R f² dt [J/N²] (Q: twice the building's energy)
  int output_every = 8;
  std::string output;            ///< folder for structure.csv, structure.json and structure.md
  std::string format = "md";
};

/// The two runs a structure command makes: the bare building and the building with the damper.
struct StructureResult {
  LoadedModel damper_model;               ///< owns the model run.damper points to
  structure::SeismicRun run;              ///< with the damper (run.damper set)
  structure::SeismicResponse bare, damped;
  std::string damper_id;
  double lqr_residual = 0;                ///< the Riccati residual of the on/off rule's gain (0: passive)
};

void add_structure_options(CLI::App* cmd, StructureOptions& options);
/// Checks the options, reads the building, the record and the model, and runs both (the Python module's too).
StructureResult run_structure(const StructureOptions& options);
int structure_command(const StructureOptions& options);

}  // namespace dampbench::cli
