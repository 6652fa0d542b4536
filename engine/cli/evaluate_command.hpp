#pragma once
// `dampbench evaluate`: every metric of given parameters on one or more records (no optimization).
#include <string>
#include <vector>

#include "engine/record/record_options.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

struct EvaluateOptions {
  std::string model;
  std::string laws;
  std::string params;
  std::string model_file;  ///< a model file (fit --save-model) instead of model, laws and params
  std::vector<std::string> paths;
  RecordOptions data;
  std::string format = "md";
};

void add_evaluate_options(CLI::App* cmd, EvaluateOptions& options);
int evaluate_command(const EvaluateOptions& options);

}  // namespace dampbench::cli
