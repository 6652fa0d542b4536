#pragma once
// A trained LS-SVM model (engine/lssvm) as a file: what `lssvm --save-model` writes and `evaluate --model-file` and
// `simulate --model-file` read, so that the model predicts other records without being trained again, with the same
// bits as the training command's own test predictions. JSON, every number written with 17 significant digits
// (exact_json_text): the lag orders, c and σ, the inputs' normalization, the normalized training points, the
// coefficients α and b, and the records it was trained on.
#include <string>
#include <vector>

#include "engine/lssvm/lssvm.hpp"

namespace dampbench {

inline constexpr const char* kLssvmModelFileFormat = "dampbench-lssvm-model";
inline constexpr int kLssvmModelFileVersion = 1;

/// The file's text.
std::string lssvm_model_file_text(const lssvm::Model& model, const std::vector<std::string>& trained_on,
                                  const std::string& dampbench_version);

/// Writes the file whole or not at all (write_text_file).
void write_lssvm_model_file(const std::string& path, const lssvm::Model& model,
                            const std::vector<std::string>& trained_on, const std::string& dampbench_version);

/// A file's text parsed into the model; InputError "<source>: key '<key>': <what was expected>".
lssvm::Model parse_lssvm_model_file(const std::string& text, const std::string& source);

/// Reads and parses a file.
lssvm::Model load_lssvm_model_file(const std::string& path);

/// Whether the file at `path` says it is an LS-SVM model (its "format"); false for another file or one that does
/// not read as JSON (its own reader then says what is wrong).
bool is_lssvm_model_file(const std::string& path);

}  // namespace dampbench
