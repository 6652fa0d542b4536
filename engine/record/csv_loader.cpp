#include "engine/record/csv_loader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <optional>

#include <fmt/format.h>

#include "engine/record/differentiate.hpp"
#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/record/units.hpp"

namespace dampbench {
namespace {

/// A line that carries content (not a comment, not blank), with its 1-based number in the file.
struct Line {
  std::size_t number = 0;
  std::string text;
};

/// One column of the file: its name, its unit, where that unit came from (for messages), and the SI factor.
struct ColumnInfo {
  std::string name;
  std::string unit;         ///< empty = SI
  std::string unit_origin;  ///< message prefix naming where the unit was given
  double factor = 1.0;
};

constexpr std::size_t kMinSamplesForDerivatives = 4;

/// Runs `fn`, prefixing the message of any InputError it throws with `where`.
template <class Fn>
auto with_prefix(std::string_view where, Fn&& fn) {
  try {
    return fn();
  } catch (const InputError& error) {
    throw InputError(fmt::format("{}: {}", where, error.what()));
  }
}

/// unit_to_si with `where` prefixed to its messages.
double factor_to_si(std::string_view where, std::string_view column, std::string_view unit) {
  return with_prefix(where, [&] { return unit_to_si(column, unit); });
}

std::string at_line(const std::string& source, std::size_t line) { return fmt::format("{}:{}", source, line); }

std::string join_quoted(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) text += fmt::format("{}'{}'", text.empty() ? "" : ", ", name);
  return text;
}

/// Content lines of the stream: comment ('#') and blank lines dropped, a UTF-8 byte-order mark removed.
/// Comments of the form "# operating: I=0.5,amp=0.01" are kept in `operating` (their text after the colon).
std::vector<Line> read_content_lines(std::istream& in, std::vector<Line>& operating) {
  std::vector<Line> lines;
  std::string text;
  constexpr std::string_view kOperating = "operating:";
  for (std::size_t number = 1; std::getline(in, text); ++number) {
    if (number == 1 && text.starts_with("\xEF\xBB\xBF")) text.erase(0, 3);
    const std::string_view content = trim(text);
    if (!content.empty() && content.front() == '#') {
      const std::string_view comment = trim(content.substr(1));
      if (comment.starts_with(kOperating)) operating.push_back({number, std::string(trim(comment.substr(kOperating.size())))});
      continue;
    }
    if (content.empty()) continue;
    lines.push_back({number, std::string(content)});
  }
  return lines;
}

/// Operating variables from "# operating: I=0.5,amp=0.01,freq=1" comments (SI: A, V, deg, m, Hz).
void read_operating(const std::vector<Line>& comments, const std::string& source, Dataset& data) {
  for (const Line& c : comments) {
    const std::string where = fmt::format("{}:{}: operating", source, c.number);
    for (const auto& [name, value] : parse_key_values(c.text, where)) {
      if (name != "I" && name != "V" && name != "phi" && name != "amp" && name != "freq")
        throw InputError(fmt::format("{}: unknown operating variable '{}' (known: I, V, phi, amp, freq)", where, name));
      data.operating[name] = parse_number(value, fmt::format("{} {}", where, name));
      data.operating_source[name] = "file comment";
      data.operating_refused.erase(name);  // the file states the constant its column could not give
      data.operating_signals.erase(name);
    }
  }
}

bool is_header(const std::vector<std::string_view>& cells) {
  return std::any_of(cells.begin(), cells.end(),
                     [](std::string_view cell) { return try_parse_number(cell).status == NumberStatus::not_a_number; });
}

/// A column from "x" or "x[mm]"; `origin` prefixes messages about it.
ColumnInfo column_from_cell(std::string_view cell, const std::string& origin) {
  auto [name, unit] = with_prefix(origin, [&] { return split_name_unit(cell); });
  return {std::move(name), std::move(unit), origin, 1.0};
}

/// Rejects names other than t, x, v, a, F, y, u, I, V, phi (listing all of them) and repeated names.
void check_names(const std::vector<ColumnInfo>& columns, const std::string& origin) {
  std::vector<std::string> unknown;
  for (const auto& column : columns)
    if (!is_known_column(column.name)) unknown.push_back(column.name);
  if (!unknown.empty())
    throw InputError(fmt::format("{}: unknown column{} {} (known: {})", origin, unknown.size() > 1 ? "s" : "",
                                 join_quoted(unknown), known_columns_text()));
  for (std::size_t i = 0; i < columns.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (columns[i].name == columns[j].name)
        throw InputError(fmt::format("{}: column '{}' given twice", origin, columns[i].name));
}

/// The columns named by the header line (if any) and options.columns; throws when neither names them.
std::vector<ColumnInfo> name_columns(const std::optional<Line>& header, bool comma_separated, const CsvOptions& options,
                                     const std::string& source) {
  const std::string option_origin = source + ": --columns";
  std::vector<ColumnInfo> columns;
  if (header) {
    const std::string origin = at_line(source, header->number);
    for (std::string_view cell : split_cells(header->text, comma_separated))
      columns.push_back(column_from_cell(cell, origin));
    if (options.columns.empty()) {
      check_names(columns, origin);
      return columns;
    }
    if (options.columns.size() != columns.size())
      throw InputError(fmt::format("{}: --columns gives {} names but the header has {} columns", origin,
                                   options.columns.size(), columns.size()));
  } else if (options.columns.empty()) {
    throw InputError(fmt::format(
        "{}: no header row and no --columns given; expected a header like t,x,F or --columns t,x,v,F", source));
  }
  columns.resize(options.columns.size());
  for (std::size_t i = 0; i < options.columns.size(); ++i) {
    ColumnInfo renamed = column_from_cell(options.columns[i], option_origin);
    if (renamed.unit.empty())
      columns[i].name = std::move(renamed.name);  // keeps the header's unit, if any
    else
      columns[i] = std::move(renamed);
  }
  check_names(columns, option_origin);
  return columns;
}

/// Applies options.units (validated here, even for columns the file lacks) and computes the SI factors.
void assign_units(std::vector<ColumnInfo>& columns, const CsvOptions& options, const std::string& source) {
  const std::string units_origin = source + ": --units";
  for (const auto& [name, unit] : options.units) factor_to_si(units_origin, name, unit);
  for (auto& column : columns) {
    if (const auto found = options.units.find(column.name); found != options.units.end()) {
      column.unit = found->second;
      column.unit_origin = units_origin;
    }
    if (!column.unit.empty()) column.factor = factor_to_si(column.unit_origin, column.name, column.unit);
  }
}

std::optional<std::size_t> index_of(const std::vector<ColumnInfo>& columns, std::string_view name) {
  for (std::size_t i = 0; i < columns.size(); ++i)
    if (columns[i].name == name) return i;
  return std::nullopt;
}

/// A record with column u is a system record (t, u, and y when the output is required); one with a column of each kind
/// is refused, since a record is either driven by displacement (rig) or by force (system).
void check_required(const std::vector<ColumnInfo>& columns, const CsvOptions& options, const std::string& source) {
  const bool system = index_of(columns, "u") || index_of(columns, "y");
  std::vector<std::string> required{"t", system ? "u" : "x"};
  if (options.require_force) required.emplace_back(system ? "y" : "F");
  std::vector<std::string> missing;
  for (const auto& name : required)
    if (!index_of(columns, name)) missing.push_back(name);
  std::string found;
  for (const auto& column : columns) found += (found.empty() ? "" : ", ") + column.name;
  if (system)
    for (const char* rig : {"x", "v", "a", "F"})
      if (index_of(columns, rig))
        throw InputError(fmt::format("{}: column '{}' with a force input u or an output y (columns found: {}); a record "
                                     "is either t,x,F (displacement in, force out: a rig) or t,y,u (force u in, "
                                     "displacement y out: a system)",
                                     source, rig, found));
  if (missing.empty()) return;
  throw InputError(fmt::format("{}: missing column{} {} (columns found: {})", source, missing.size() > 1 ? "s" : "",
                               join_quoted(missing), found));
}

/// One cell in SI units; `index` is 0-based (messages count from 1).
double parse_cell(std::string_view cell, std::size_t index, const ColumnInfo& column, const std::string& where) {
  const ParsedNumber parsed = try_parse_number(cell);
  const auto fail = [&](std::string_view what) {
    return InputError(fmt::format("{}: column {} ('{}'): {}", where, index + 1, column.name, what));
  };
  if (parsed.status == NumberStatus::not_a_number) throw fail(fmt::format("expected a number, got '{}'", cell));
  if (parsed.status == NumberStatus::out_of_range) throw fail(fmt::format("value out of range ('{}')", cell));
  if (!std::isfinite(parsed.value)) throw fail(fmt::format("value is not finite ('{}')", cell));
  return parsed.value * column.factor;
}

/// Appends the values of one data line to `values` (one vector per column).
void read_row(const Line& line, bool comma_separated, const std::vector<ColumnInfo>& columns, const std::string& source,
              std::vector<std::vector<double>>& values) {
  const std::string where = at_line(source, line.number);
  const auto cells = split_cells(line.text, comma_separated);
  if (cells.size() != columns.size())
    throw InputError(fmt::format("{}: expected {} values, got {}", where, columns.size(), cells.size()));
  for (std::size_t i = 0; i < cells.size(); ++i) values[i].push_back(parse_cell(cells[i], i, columns[i], where));
}

void check_time_step(const std::vector<double>& t_s, const std::string& source, std::size_t line) {
  if (t_s.size() < 2) return;
  const double previous = t_s[t_s.size() - 2];
  const double current = t_s.back();
  if (!(current > previous))
    throw InputError(
        fmt::format("{}: time must increase strictly ({:g} s after {:g} s)", at_line(source, line), current, previous));
}

double mean(const std::vector<double>& values) {
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

/// A column of I, V or phi gives one constant (its mean) only when it stays within measurement noise: its spread
/// max − min at most kConstantSpreadRel of max(|mean|, kConstantFloor) (A, V or degrees; the floor keeps a 0 A
/// test's noise from counting as variation). A column beyond that is a time-varying current, voltage or angle:
/// the mean stays in `operating` (for tables), the column in `operating_signals` (a law model follows it sample by
/// sample), and `operating_refused` says why a model that cannot be stepped must not use it.
constexpr double kConstantSpreadRel = 0.05;
constexpr double kConstantFloor = 0.1;

void read_operating_column(const char* name, const std::vector<double>& column, Dataset& data) {
  const double m = mean(column);
  const auto [lo, hi] = std::minmax_element(column.begin(), column.end());
  const double spread = *hi - *lo, scale = std::max(std::fabs(m), kConstantFloor);
  data.operating[name] = m;
  data.operating_source[name] = "column mean";
  if (!(spread <= kConstantSpreadRel * scale)) {
    data.operating_signals[name] = column;
    data.operating_source[name] =
        fmt::format("column varying from {:.6g} to {:.6g}: the mean shown, laws follow the column sample by sample", *lo, *hi);
    data.operating_refused[name] = fmt::format(
        "{}: column {} varies over the test (min {:.6g}, max {:.6g}: spread {:.3g} is {:.3g} % of max(|mean|, {:g}), "
        "more than the {:g} % a constant value may vary); a law in it follows the column sample by sample, which "
        "needs a model that can be stepped",
        data.source, name, *lo, *hi, spread, 100 * spread / scale, kConstantFloor, 100 * kConstantSpreadRel);
  }
}

/// x, F, v and a of a rig record, computing v and a when the file lacks them.
template <class Column>
void fill_rig_columns(const Column& column, Dataset& data) {
  data.x_m = std::move(*column("x"));
  if (auto* force = column("F")) data.F_N = std::move(*force);
  if (auto* velocity = column("v"))
    data.v_m_s = std::move(*velocity);
  else
    data.v_m_s = differentiate_3rd_order(data.t_s, data.x_m);
  if (auto* acceleration = column("a"))
    data.a_m_s2 = std::move(*acceleration);
  else
    data.a_m_s2 = differentiate_3rd_order(data.t_s, data.v_m_s);
}

/// Moves the parsed columns into a Dataset: a system record's t, u, y, or a rig record's columns.
Dataset make_dataset(const std::vector<ColumnInfo>& columns, std::vector<std::vector<double>>& values,
                     const std::string& source) {
  const auto column = [&](std::string_view name) -> std::vector<double>* {
    const auto index = index_of(columns, name);
    return index ? &values[*index] : nullptr;
  };
  Dataset data;
  data.source = source;
  data.name = std::filesystem::path(source).stem().string();
  data.t_s = std::move(*column("t"));
  if (auto* input = column("u")) {
    data.u_N = std::move(*input);
    if (auto* output = column("y")) data.y_m = std::move(*output);
  } else {
    fill_rig_columns(column, data);
  }
  for (const char* name : {"I", "V", "phi"})
    if (const auto* operating = column(name)) read_operating_column(name, *operating, data);
  return data;
}

}  // namespace

std::vector<std::string_view> split_cells(std::string_view line, bool comma_separated) {
  std::vector<std::string_view> cells;
  if (comma_separated) {
    for (std::size_t start = 0;;) {
      const std::size_t comma = line.find(',', start);
      cells.push_back(trim(line.substr(start, comma == std::string_view::npos ? comma : comma - start)));
      if (comma == std::string_view::npos) return cells;
      start = comma + 1;
    }
  }
  constexpr std::string_view blanks = " \t\r\n\v\f";
  for (std::size_t start = line.find_first_not_of(blanks); start != std::string_view::npos;) {
    const std::size_t end = line.find_first_of(blanks, start);
    cells.push_back(line.substr(start, end == std::string_view::npos ? end : end - start));
    start = line.find_first_not_of(blanks, end);
  }
  return cells;
}

std::map<std::string, std::string> parse_units_option(std::string_view text) {
  std::map<std::string, std::string> units;
  for (auto& [column, unit] : parse_key_values(text, "--units")) {
    factor_to_si("--units", column, unit);
    units.emplace(std::move(column), std::move(unit));
  }
  return units;
}

Dataset parse_csv(std::istream& in, const std::string& source, const CsvOptions& options) {
  std::vector<Line> operating;
  const std::vector<Line> lines = read_content_lines(in, operating);
  if (lines.empty()) throw InputError(fmt::format("{}: no data (the file is empty or has only comments)", source));
  const bool comma_separated = lines.front().text.find(',') != std::string::npos;
  std::optional<Line> header;
  if (is_header(split_cells(lines.front().text, comma_separated))) header = lines.front();

  std::vector<ColumnInfo> columns = name_columns(header, comma_separated, options, source);
  assign_units(columns, options, source);
  check_required(columns, options, source);

  const std::size_t t_index = *index_of(columns, "t");
  std::vector<std::vector<double>> values(columns.size());
  for (std::size_t i = header ? 1 : 0; i < lines.size(); ++i) {
    read_row(lines[i], comma_separated, columns, source, values);
    check_time_step(values[t_index], source, lines[i].number);
  }
  const std::size_t samples = values[t_index].size();
  const std::size_t needed = std::max(options.min_samples, kMinSamplesForDerivatives);
  if (samples < needed)
    throw InputError(fmt::format("{}: {} samples; at least {} are needed", source, samples, needed));
  Dataset data = make_dataset(columns, values, source);
  read_operating(operating, source, data);
  return data;
}

Dataset dataset_from_columns(const std::map<std::string, std::vector<double>>& si_columns, const std::string& name,
                             const CsvOptions& options) {
  const std::string source = fmt::format("record '{}'", name);
  std::vector<ColumnInfo> columns;
  std::vector<std::vector<double>> values;
  for (const auto& [column, data] : si_columns) {
    columns.push_back({column, "", "", 1.0});
    values.push_back(data);
  }
  check_names(columns, source);
  check_required(columns, options, source);
  const std::size_t samples = values[*index_of(columns, "t")].size();
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (values[i].size() != samples)
      throw InputError(fmt::format("{}: column '{}' has {} samples and column 't' {}", source, columns[i].name,
                                   values[i].size(), samples));
    for (std::size_t k = 0; k < samples; ++k)
      if (!std::isfinite(values[i][k]))
        throw InputError(fmt::format("{}: column '{}', sample {}: value is not finite ({})", source, columns[i].name,
                                     k, values[i][k]));
  }
  const std::vector<double>& t_s = values[*index_of(columns, "t")];
  for (std::size_t k = 1; k < samples; ++k)
    if (!(t_s[k] > t_s[k - 1]))
      throw InputError(fmt::format("{}: time must increase strictly ({:g} s at sample {} after {:g} s)", source, t_s[k],
                                   k, t_s[k - 1]));
  const std::size_t needed = std::max(options.min_samples, kMinSamplesForDerivatives);
  if (samples < needed) throw InputError(fmt::format("{}: {} samples; at least {} are needed", source, samples, needed));
  Dataset data = make_dataset(columns, values, source);
  data.name = name;
  data.source = "arrays";
  for (auto& [variable, where] : data.operating_source)
    if (!data.operating_signals.count(variable)) where = "array mean";
  return data;
}

Dataset load_csv(const std::string& path, const CsvOptions& options) {
  std::ifstream file(path);
  if (!file) throw InputError(fmt::format("cannot open data file '{}'", path));
  return parse_csv(file, path, options);
}

}  // namespace dampbench
