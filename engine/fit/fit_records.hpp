#pragma once
// The records of a fit named by their files (the command line's --data): each loaded with the same loader
// options, prepared, and checked against the model.
#include <string>
#include <string_view>
#include <vector>

#include "engine/model/model.hpp"
#include "engine/record/record_options.hpp"
#include "engine/record/signals.hpp"

namespace dampbench {

struct FitRecords {
  std::vector<Signals> signals;
  std::string names;  ///< the records' names joined by '+' (they name the task: task_key)
  [[nodiscard]] std::vector<const Signals*> pointers() const;
  [[nodiscard]] double samples() const;  ///< over every record
};

/// Loads `paths` with the loader options `data` (its path unused), in order, each checked against the model
/// (check_record) as soon as it is read. Every record needs its measured output (F, or y of a system record).
FitRecords load_fit_records(const Model& model, const std::vector<std::string>& paths, const RecordOptions& data);

/// The same from records already loaded (the Python module's): each prepared and checked against the model.
FitRecords fit_records_of(const Model& model, const std::vector<Dataset>& records);

/// A command's records: its files (`paths`, read with `data`) or records already loaded, exactly one of the two.
/// InputError "<command>: give at least one --data FILE" for neither.
FitRecords command_records(const Model& model, const std::vector<std::string>& paths,
                           const std::vector<Dataset>& records, const RecordOptions& data, std::string_view command);

}  // namespace dampbench
