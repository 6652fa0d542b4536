#pragma once
// How one record file is read and prepared: the loader options shared by `fit`, `simulate`, `lssvm`,
// `compare` and every [[datasets]] entry of a sweep file.

#include <string>
#include <string_view>
#include <vector>

#include "engine/record/dataset.hpp"
#include "engine/record/record_source.hpp"

namespace dampbench {

/// Loads and prepares the records of one file (engine/record/record_files.hpp): several when a column range or
/// `split` makes them. `set` may give one value per record ("I=0,0.25,0.5"). Throws InputError naming the option or
/// the file and line.
std::vector<Dataset> load_records(const RecordOptions& options, bool require_force);

/// The one record of a file: load_records, refused with a message when the file gives several.
Dataset load_record(const RecordOptions& options, bool require_force);

/// The preparation steps of load_record after the file is read: slider-crank transform → cycle averaging →
/// operating variables (utfsm conditions from the record's name, then --set). Records made from arrays take them
/// too.
Dataset prepare_record(Dataset data, const RecordOptions& options);

/// Applies "I=1,amp=0.01" to a dataset's operating variables (InputError for unknown names).
void set_operating(Dataset& data, const std::string& text, std::string_view option = "--set");

}  // namespace dampbench
