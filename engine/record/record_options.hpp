#pragma once
// How one record file is read and prepared: the loader options shared by `fit`, `simulate`, `lssvm`,
// `compare` and every [[datasets]] entry of a sweep file.

#include <string>
#include <string_view>
#include <vector>

#include "engine/record/dataset.hpp"

namespace dampbench {

/// Where a record comes from and how it is prepared.
struct RecordOptions {
  std::string path;        ///< file path
  std::string units;       ///< "x=mm,F=kN"
  std::string columns;     ///< "t,x,v,F"
  std::string transform;   ///< "" | "slider-crank" | "slider-crank-printed" (crfd rig, eqs. 2.1–2.2)
  std::string average;     ///< "cycles=10,drop=3": average the kept cycles into one
  std::string conditions;  ///< "" | "utfsm": operating variables from the file name
  std::string set;         ///< "I=1,amp=0.01,freq=1": operating variables (override the others)
  bool periodic = false;   ///< a system record is one period of a periodic input (Dataset::periodic_input)
  // A rig's raw export or a MATLAB file (engine/record/record_files.hpp):
  int skip_header = -1;     ///< lines before a text export's column names; -1: detect a "Header Size: N" block
  std::string scale;        ///< "x=10e-3,F=980.665": gains applied to the file's values, before `units`
  std::string split;        ///< "" | "events" (between DAQ Pause and Resume) | "nan" (between rows of NaN)
  int smooth_samples = 0;   ///< centred moving average of x and F over this many samples (0: none)
  std::string remove_mean;  ///< "x,F": columns whose mean is removed
  bool whole_cycles = false;///< trim to whole cycles of x (first to last upward crossing of its mean)
};

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
