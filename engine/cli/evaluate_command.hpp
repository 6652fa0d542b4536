#pragma once
// `dampbench evaluate`: every metric of given parameters on one or more records (no optimization).
#include <string>
#include <vector>

#include "engine/evaluation/batch_evaluator.hpp"
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
  std::vector<Dataset> records;  ///< records already loaded, instead of paths (the Python module's)
  RecordOptions data;
  std::string format = "md";
};

/// The metrics of an evaluation, as `dampbench evaluate` prints them.
struct Evaluation {
  std::string model_id;
  std::vector<std::string> names;  ///< each record's name (a file's stem)
  std::vector<MetricRow> metrics;  ///< per record, every metric in the order of kAllMetrics
  /// With --model-file: per record, its law variables outside the range the model was fitted on ("" inside;
  /// FittedRange::outside). Empty without a model file.
  std::vector<std::string> extrapolated = {};
};

void add_evaluate_options(CLI::App* cmd, EvaluateOptions& options);

/// Checks the options, builds the model and loads the records, and evaluates every metric on each record (the
/// Python module's evaluate too).
Evaluation run_evaluate(const EvaluateOptions& options);

int evaluate_command(const EvaluateOptions& options);

}  // namespace dampbench::cli
