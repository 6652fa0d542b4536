#pragma once
// How one record file is read and prepared: the loader options shared by `fit`, `simulate`, `lssvm`,
// `compare` and every [[datasets]] entry of a sweep file.

#include <string>
#include <string_view>

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
};

/// Loads and prepares one record: CSV → slider-crank transform → cycle averaging → operating variables.
/// Throws InputError naming the option or the file and line.
Dataset load_record(const RecordOptions& options, bool require_force);

/// The preparation steps of load_record after the file is read: slider-crank transform → cycle averaging →
/// operating variables (utfsm conditions from the record's name, then --set). Records made from arrays take them
/// too.
Dataset prepare_record(Dataset data, const RecordOptions& options);

/// Applies "I=1,amp=0.01" to a dataset's operating variables (InputError for unknown names).
void set_operating(Dataset& data, const std::string& text, std::string_view option = "--set");

}  // namespace dampbench
