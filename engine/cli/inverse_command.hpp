#pragma once
// `dampbench inverse`: the command (I, V or phi) that makes an identified damper give a desired force over a
// motion (engine/control/inverse.hpp), with the tracking error where the force is reachable and the shares of the
// samples at either end of the range.
#include <optional>
#include <string>

#include "engine/cli/cli_options.hpp"
#include "engine/control/inverse.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

struct InverseOptions {
  ModelByName damper;
  RecordOptions data;          ///< t, x, v and the desired force F
  std::optional<Dataset> record;  ///< a record already loaded, instead of data.path (the Python module's)
  std::string range;           ///< "I=0:1"
  std::string law = "inverse"; ///< inverse or on-off
  int substeps = 4;
  std::string output;          ///< CSV: t, the command, F_desired, F_model, reachable
  std::string format = "md";
};

struct InverseRun {
  LoadedModel model;
  Dataset record;
  control::InverseSettings settings;
  control::InverseResult result;
};

void add_inverse_options(CLI::App* cmd, InverseOptions& options);
/// Checks the options, loads the model and the record, and computes the command (the Python module's too).
InverseRun run_inverse(const InverseOptions& options);
int inverse_command(const InverseOptions& options);

}  // namespace dampbench::cli
