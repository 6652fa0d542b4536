#pragma once
// Records from the files engineers have: a MATLAB .mat file (engine/record/mat_file.hpp), a rig's text export with a
// header block, named or numbered channels, gains, events and several tests (engine/record/text_channels.hpp), or
// a plain record file (engine/record/csv_loader.hpp). The --columns mapping (engine/record/column_map.hpp) picks the
// record's columns from the file's channels; a column range or --split gives several records, named
// "<file stem>#k" (k from 1); the preprocessing options (engine/record/preprocess.hpp) apply to each.
#include <vector>

#include "engine/record/channel_table.hpp"
#include "engine/record/dataset.hpp"
#include "engine/record/record_source.hpp"

namespace dampbench {

/// The records of options.path in SI units, before prepare_record (transform, averaging, operating variables).
std::vector<Dataset> read_record_file(const RecordOptions& options, bool require_force);

/// The records a table of channels gives under options' --columns mapping, --scale, --units, --split and
/// preprocessing (read_record_file's work after reading the file).
std::vector<Dataset> records_from_channels(const ChannelTable& table, const RecordOptions& options, bool require_force);

/// Operating variables with one value for every record or one per record: "I=0,0.25,0.5,amp=0.01" (a value without
/// a name continues the list of the name before it). Throws InputError naming `option` for unknown names, a list
/// whose length is not 1 or `records`, and values that are not numbers.
std::vector<std::string> operating_per_record(const std::string& text, std::size_t records,
                                              std::string_view option = "--set");

}  // namespace dampbench
