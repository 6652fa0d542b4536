#pragma once
// The --columns mapping of a record file whose channels are not named t, x, F, ...: "t=time,x=data[:,0],F=data[:,3]"
// picks each record column from a channel of the file (a MATLAB variable or struct field "s.x", a text column by
// header name or by number "#k", k from 0), a matrix's column or row, or a range of them ("F=data[:,1:6]": one
// record per column, Python's slices: 0-based, end excluded), or the same field of every element of a struct array
// ("x=tests(:).x": one record per element, MATLAB's s(1), s(2), ...).
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "engine/record/channel_table.hpp"

namespace dampbench {

/// One record column taken from the file.
struct ColumnPick {
  enum class Axis { whole, column, row };
  std::string column;   ///< t, x, v, a, F, y, u, I, V, phi
  std::string channel;  ///< variable or header name; "#k" for the file's k-th column
  Axis axis = Axis::whole;
  std::size_t first = 0, last = 1;  ///< the columns (Axis::column) or rows (Axis::row) [first, last)
  bool range = false;               ///< written as a:b: gives one record per index
  std::string text;                 ///< as written, for messages
  std::string unit;                 ///< a header cell's unit ("x[mm]"), which --units overrides
};

/// "data (10x3), time (10x1), label (char)": what a file holds, for messages.
std::string channel_list(const ChannelTable& table);

/// True when --columns maps names to channels ("t=time,...") rather than naming the file's columns in order.
bool is_column_map(std::string_view text);

/// Parses "t=time,x=data[:,0],F=data[:,1:6]" (commas inside brackets belong to the index). Throws InputError
/// naming `option` and the entry: unknown record column, a column given twice, a malformed index.
std::vector<ColumnPick> parse_column_map(std::string_view text, std::string_view option = "--columns");

/// The vectors a pick gives from the table: one, or one per index of a range or element of a struct array. Throws InputError starting with the
/// table's source: a channel that is not there (listing those that are), an index out of range (with the matrix's
/// size), a matrix picked whole that is not a vector.
std::vector<std::vector<double>> pick_vectors(const ChannelTable& table, const ColumnPick& pick);

}  // namespace dampbench
