#pragma once
// `dampbench export`: an identified model as a dependency-free C99 pair for a controller or a real-time target
// (engine/export/c_export.hpp).
#include <optional>
#include <string>

#include "engine/cli/cli_options.hpp"
#include "engine/export/c_export.hpp"
#include "engine/export/fixed_step_check.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

struct ExportOptions {
  ModelByName model;
  std::string lang = "c";
  int substeps = 4;     ///< RK4 sub-steps per dbm_step
  /// The motion the step size is checked on; by default the fitted records' largest (model file).
  std::optional<double> stroke_m, velocity_m_s;
  std::string output;   ///< folder for dampbench_model.h and dampbench_model.c
};

/// The C pair of the named model, not written (the command's files, the Python module's strings) and the model id.
struct ExportedModel {
  exporting::CSource c;
  std::string model_id;
  exporting::FixedStepCheck check;  ///< the step size checked (has_states with dt_tried_last_s 0: not checked)
};

void add_export_options(CLI::App* cmd, ExportOptions& options);
/// Checks --lang, loads the model and writes it as C in memory; InputError for what the exporter does not cover.
ExportedModel run_export(const ExportOptions& options);
int export_command(const ExportOptions& options);

}  // namespace dampbench::cli
