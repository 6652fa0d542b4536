#pragma once
// What the command line or a sweep file says about one record file (RecordOptions), apart from the functions that
// load it (record_options.hpp) and read its formats (record_files.hpp), which both take it.
#include <string>

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

}  // namespace dampbench
