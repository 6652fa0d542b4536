#pragma once
// Loading test records (CSV or whitespace-separated text) into a Dataset in SI units.
#include <cstddef>
#include <istream>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "engine/record/dataset.hpp"

namespace dampbench {

/// How to read a record file; the defaults read a file with a header row in SI units.
struct CsvOptions {
  std::map<std::string, std::string> units;  ///< column → unit, overrides header units (--units x=mm,F=kN)
  std::vector<std::string> columns;  ///< names for a header-less file (--columns t,x,v,F); may carry units "x[mm]"
  bool require_force = true;         ///< fit needs F; simulate --input does not
  std::size_t min_samples = 8;       ///< fewer samples is an error (never fewer than 4: derivatives need them)
};

/// Cells of a line of a record file: comma-separated (each trimmed) or separated by runs of whitespace.
std::vector<std::string_view> split_cells(std::string_view line, bool comma_separated);

/// Parses --units "x=mm,F=kN" into CsvOptions::units (validating column and unit names).
std::map<std::string, std::string> parse_units_option(std::string_view text);

/// Loads a test record and converts it to SI. A rig record needs columns t and x (F too if require_force);
/// v and a are taken from the file when present, else computed by differentiate_3rd_order (v from x,
/// a from the velocity in use). A system record (a column u or y) needs t and u (y too if require_force) and
/// no x, v, a or F. Unknown column names in a header are an error naming them (only t, x, v, a,
/// F, y, u, I, V, phi). Columns I, V, phi (if present) go to Dataset::operating as their mean value.
/// dataset.name = file stem, source = path. Every error is an InputError starting with the path.
///
/// Format: '#' lines and blank lines are skipped; the first remaining line decides the separator (comma if it
/// has one, else runs of whitespace) and is a header if any cell is not a number. With a header,
/// options.columns (if given) renames the columns positionally; without one, options.columns is required.
/// Units come from the header ("x[mm]"), then options.columns, then options.units (last wins); SI if none.
Dataset load_csv(const std::string& path, const CsvOptions& options);

/// Same, from a stream; `source` is the name used in messages (and its stem the dataset name).
Dataset parse_csv(std::istream& in, const std::string& source, const CsvOptions& options);

/// A record from columns already in SI units, named by `name` (the Python module's arrays): t and x required (F
/// with options.require_force), the same column names, checks (finite values, time strictly increasing, enough
/// samples) and derivatives as a file. options.units and options.columns are not used. Messages start with
/// "record 'NAME'".
Dataset dataset_from_columns(const std::map<std::string, std::vector<double>>& si_columns, const std::string& name,
                             const CsvOptions& options);

}  // namespace dampbench
