#pragma once
// What a record file holds before it is a record: named numeric channels (a text file's columns, a MATLAB file's
// variables), the text events of a rig export's rows, and the sampling interval its header block states.
// engine/record/record_files.hpp turns a table into records with the --columns mapping.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace dampbench {

/// A rows × cols matrix of numbers, column-major (a text column or a MATLAB vector is rows × 1 or 1 × cols).
struct Channel {
  std::size_t rows = 0, cols = 0;
  std::vector<double> values;  ///< values[row + col * rows]

  [[nodiscard]] double at(std::size_t row, std::size_t col) const { return values[row + col * rows]; }
};

struct ChannelTable {
  std::string source;                        ///< the file's path, for messages
  std::vector<std::string> names;            ///< channel names in the file's order
  std::map<std::string, Channel> channels;   ///< by name
  std::vector<std::string> skipped;          ///< variables or columns that are not numeric (named in messages)
  std::vector<std::string> events;           ///< per row, a rig export's events cell ("" for none); empty otherwise
  std::optional<double> sampling_interval_s; ///< a header block's "Sampling Interval"
};

}  // namespace dampbench
