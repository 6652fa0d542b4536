#pragma once
// A fitted model as a file: what `fit --save-model` writes and `evaluate --model-file` and `simulate
// --model-file` read, so that a model identified once predicts other records (a controller's or a structural
// simulation's) without being fitted again. JSON (docs/guide.md shows the layout): the model by its names
// (base id, laws, or fixture), the coefficients by name, every number written with 17 significant digits so that
// it reads back to the same bits, the metric on each fitted record and where each operating variable came from.
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/fit/fitted_range.hpp"
#include "engine/fit/resolve_model.hpp"
#include "engine/record/signals.hpp"

namespace dampbench {

inline constexpr const char* kModelFileFormat = "dampbench-model";
inline constexpr int kModelFileVersion = 1;

/// One record the model was fitted on: its metric at the coefficients and its operating variables.
struct ModelFileRecord {
  std::string name;          ///< the record's name (file stem)
  std::string path;          ///< the file as the command line gave it
  double metric_value = 0;   ///< the fit's metric on this record alone (what `evaluate` prints for it)
  nlohmann::ordered_json operating;  ///< operating_json of the record
  /// The record's motion, what `export` checks its step size on (0 in a file written before the key existed).
  double displacement_ptp_m = 0;
  double velocity_max_abs_m_s = 0;
};

struct ModelFile {
  std::string dampbench_version;  ///< the binary that fitted it
  std::string vector_level;       ///< the kernels' instruction set it ran at (same bits only at the same level)
  ModelChoice choice;             ///< base model id or fixture, and the laws text as given
  std::string model_id;           ///< the resolved model's id (information: reading rebuilds it from `choice`)
  std::vector<std::pair<std::string, double>> coefficients;  ///< by name, in the model's parameter order
  std::string metric;             ///< the metric the fit minimized
  double fitted_value = 0;        ///< its value on all fitted records together (what `fit` reports)
  std::vector<ModelFileRecord> records;
};

/// The record's law variables with their sources: {"I": {"value": 0.5, "source": "--set"}, ...}.
nlohmann::ordered_json operating_json(const Signals& record);

/// JSON text with every floating-point number as "%.17g" (non-finite as null), so that it reads back to the same bits
/// in any language: the model files' writer.
std::string exact_json_text(const nlohmann::ordered_json& j);

/// The file's text: JSON with every floating-point number as "%.17g".
std::string model_file_text(const ModelFile& file);

/// Writes the file whole or not at all (write_text_file).
void write_model_file(const std::string& path, const ModelFile& file);

/// A model file parsed; InputError "<path>: <key>: <what was expected>" for a missing key or a wrong type.
/// `source` names the file in messages.
ModelFile parse_model_file(const std::string& text, const std::string& source);

/// The model of a file made ready to evaluate: the model rebuilt from its names and the coefficients in its
/// parameter order.
struct LoadedModel {
  ModelFile file;
  ResolvedModel model;
  std::vector<double> params;
};

/// Reads, parses and resolves a model file; InputError naming the file and the key for an unknown model, laws
/// that no longer parse, or coefficients that are not the model's (missing, unknown or not numbers).
LoadedModel load_model_file(const std::string& path);

/// The range of the model's law variables over the records the file says it was fitted on (their "operating").
FittedRange fitted_range_of(const LoadedModel& loaded);

}  // namespace dampbench
