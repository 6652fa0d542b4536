#pragma once
// `dampbench sensitivity`: differential sensitivity of a model's parameters (crfd eqs. 4.1-4.3) over one or more
// cases (parameters + input); SP is reported per case and averaged (crfd averages 1 Hz–1 mm and 3 Hz–3 mm).
#include <string>
#include <vector>

#include "engine/record/record_options.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

struct SensitivityOptions {
  std::string model;
  std::vector<std::string> params;  ///< one per case
  std::vector<std::string> sines;   ///< one per case (or one for all)
  std::vector<std::string> paths;   ///< records instead of sines
  RecordOptions data;                 ///< loader options for the records
  int points = 21;
  double range = 0.5;
  std::string objective = "rms";    ///< rms (of the model force) or a metric name
  bool normalized = false;
  std::string format = "md";
};

void add_sensitivity_options(CLI::App* cmd, SensitivityOptions& options);
int sensitivity_command(const SensitivityOptions& options);

}  // namespace dampbench::cli
