#include "engine/record/record_files.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/record/column_map.hpp"
#include "engine/record/csv_loader.hpp"
#include "engine/record/differentiate.hpp"
#include "engine/record/mat_file.hpp"
#include "engine/record/preprocess.hpp"
#include "engine/record/text_channels.hpp"
#include "engine/record/units.hpp"

namespace dampbench {
namespace {

using Columns = std::map<std::string, std::vector<double>>;

bool wants_preprocessing(const RecordOptions& o) {
  return o.smooth_samples != 0 || !o.remove_mean.empty() || o.whole_cycles;
}

/// The picks of `options.columns`: a mapping, the file's numeric channels in order renamed ("t,x,F"), or the channels
/// named as record columns.
std::vector<ColumnPick> picks_of(const ChannelTable& table, const RecordOptions& o) {
  if (is_column_map(o.columns)) return parse_column_map(o.columns);
  std::vector<ColumnPick> picks;
  if (!o.columns.empty()) {
    const auto names = split_list(o.columns, "--columns");
    if (names.size() > table.names.size())
      throw InputError(fmt::format("{}: --columns names {} columns; the file has {} numeric ones", table.source,
                                   names.size(), table.names.size()));
    for (std::size_t i = 0; i < names.size(); ++i)
      picks.push_back(parse_column_map(fmt::format("{}=#{}", names[i], i)).front());
    return picks;
  }
  for (const auto& name : table.names) {  // "F" or, as a record file's header has it, "F[kN]"
    std::pair<std::string, std::string> column_unit;
    try {
      column_unit = split_name_unit(name);
    } catch (const InputError&) {
      continue;  // not a record column's name
    }
    if (!is_known_column(column_unit.first) || table.channels.at(name).values.empty()) continue;
    ColumnPick pick;
    pick.column = column_unit.first;
    pick.channel = pick.text = name;
    pick.unit = column_unit.second;
    picks.push_back(std::move(pick));
  }
  if (picks.empty())
    throw InputError(fmt::format("{}: no channel is named as a record column ({}); the file holds: {}; map them "
                                 "with --columns, e.g. t=time,x=data[:,0],F=data[:,1]",
                                 table.source, known_columns_text(), channel_list(table)));
  return picks;
}

/// column → factor from "x=10e-3,F=980.665" (--scale) times the --units factor.
std::map<std::string, double> factors_of(const RecordOptions& o, const std::vector<ColumnPick>& picks) {
  std::map<std::string, double> factor;
  for (const auto& p : picks) factor[p.column] = 1.0;
  for (const auto& [column, value] : parse_key_values(o.scale, "--scale")) {
    if (!factor.count(column)) {
      std::string columns;
      for (const auto& [name, f] : factor) columns += (columns.empty() ? "" : ", ") + name;
      throw InputError(fmt::format("--scale {}: the record has no column '{}' (its columns: {})", column, column, columns));
    }
    factor[column] *= parse_number(value, "--scale " + column);
  }
  const auto units = parse_units_option(o.units);
  for (const auto& p : picks) {
    const auto given = units.find(p.column);
    const std::string& unit = given != units.end() ? given->second : p.unit;
    if (!unit.empty()) factor[p.column] *= unit_to_si(p.column, unit);
  }
  return factor;
}

/// Records before slicing: one per index of the picks' ranges (all ranges of one length).
std::vector<Columns> columns_per_record(const ChannelTable& table, const std::vector<ColumnPick>& picks,
                                        const std::map<std::string, double>& factor) {
  std::vector<Columns> records;
  for (const auto& pick : picks) {
    auto vectors = pick_vectors(table, pick);
    if (records.empty()) records.resize(vectors.size());
    if (vectors.size() != 1 && records.size() != 1 && vectors.size() != records.size())
      throw InputError(fmt::format("{}: --columns ranges of different lengths ('{}' gives {} records, another {})",
                                   table.source, pick.text, vectors.size(), records.size()));
    if (vectors.size() > records.size()) records.resize(vectors.size(), records.front());
    for (std::size_t r = 0; r < records.size(); ++r) {
      std::vector<double> v = vectors[vectors.size() == 1 ? 0 : r];
      for (double& x : v) x *= factor.at(pick.column);
      records[r][pick.column] = std::move(v);
    }
  }
  return records;
}

/// [first, last) row spans of the tests in one file: between DAQ Pause and Resume events, or between rows of NaN.
std::vector<std::pair<std::size_t, std::size_t>> segments_of(const ChannelTable& table, const Columns& columns,
                                                             const std::string& split) {
  const std::size_t n = columns.begin()->second.size();
  std::vector<std::pair<std::size_t, std::size_t>> spans;
  if (split == "events") {
    if (table.events.empty())
      throw InputError(fmt::format("{}: --split events: the file has no Events column", table.source));
    const auto has = [&](std::size_t k, std::string_view word) {
      return lowercase(table.events[k]).find(word) != std::string::npos;
    };
    bool running = true;
    std::size_t start = 0;
    for (std::size_t k = 0; k < n; ++k) {
      if (!running && has(k, "resume")) running = true, start = k;
      if (running && has(k, "pause")) {
        spans.emplace_back(start, k + 1);
        running = false;
      }
    }
    if (running && start < n) spans.emplace_back(start, n);
  } else if (split == "nan") {
    const auto finite_row = [&](std::size_t k) {
      return std::all_of(columns.begin(), columns.end(), [&](const auto& c) { return std::isfinite(c.second[k]); });
    };
    for (std::size_t k = 0; k < n;) {
      while (k < n && !finite_row(k)) ++k;
      const std::size_t start = k;
      while (k < n && finite_row(k)) ++k;
      if (k > start) spans.emplace_back(start, k);
    }
  } else {
    throw InputError(fmt::format("--split: expected events or nan, got '{}'", split));
  }
  if (spans.empty()) throw InputError(fmt::format("{}: --split {}: no test found in the file", table.source, split));
  return spans;
}

Columns slice(const Columns& columns, std::size_t first, std::size_t last) {
  Columns out;
  for (const auto& [name, v] : columns)
    out[name].assign(v.begin() + static_cast<std::ptrdiff_t>(first), v.begin() + static_cast<std::ptrdiff_t>(last));
  return out;
}

/// Smoothing, mean removal and whole cycles on a record's columns (x and F smoothed; time shifted to start at 0 when
/// the record was cut).
void preprocess(Columns& c, const RecordOptions& o, const std::string& source, bool cut) {
  if (o.smooth_samples < 0 || o.smooth_samples == 1)
    throw InputError(fmt::format("--smooth: expected a window of 2 or more samples, got {}", o.smooth_samples));
  if (o.smooth_samples > 1)
    for (const char* name : {"x", "F", "y", "u"})
      if (c.count(name)) c[name] = centred_moving_average(c[name], o.smooth_samples);
  if (!o.remove_mean.empty())
    for (const auto& name : split_list(o.remove_mean, "--remove-mean")) {
      if (!c.count(name))
        throw InputError(fmt::format("--remove-mean {}: the record has no column '{}'", name, name));
      remove_mean(c[name]);
    }
  if (o.whole_cycles) {
    if (!c.count("x")) throw InputError(fmt::format("{}: --whole-cycles needs a displacement x", source));
    const auto [first, last] = whole_cycles_span(c["x"], source);
    c = slice(c, first, last);
    cut = true;
  }
  if (cut && c.count("t")) {
    const double t0 = c["t"].front();
    for (double& t : c["t"]) t -= t0;
  }
}

}  // namespace

std::vector<Dataset> records_from_channels(const ChannelTable& table, const RecordOptions& o, bool require_force) {
  const auto picks = picks_of(table, o);
  const auto factor = factors_of(o, picks);
  std::vector<Columns> records = columns_per_record(table, picks, factor);
  // Without a time column, each record's time is k·dt from its own first sample (after any split or trim), as a
  // test converted by hand would have it.
  const bool sampled_time = !records.front().count("t");
  if (sampled_time && !table.sampling_interval_s)
    throw InputError(fmt::format("{}: no time: map t=... with --columns (no header block states a Sampling Interval)",
                                 table.source));
  bool cut = false;
  if (!o.split.empty()) {
    if (records.size() != 1)
      throw InputError(fmt::format("{}: --split and a --columns range both make several records; use one", table.source));
    std::vector<Columns> segments;
    for (const auto& [first, last] : segments_of(table, records.front(), o.split))
      segments.push_back(slice(records.front(), first, last));
    records = std::move(segments);
    cut = true;
  }
  CsvOptions csv;
  csv.require_force = require_force;
  const std::string stem = std::filesystem::path(table.source).stem().string();
  std::vector<Dataset> out;
  for (std::size_t r = 0; r < records.size(); ++r) {
    const std::string name = records.size() == 1 ? stem : fmt::format("{}#{}", stem, r + 1);
    preprocess(records[r], o, fmt::format("{} ({})", table.source, name), cut);
    if (wants_preprocessing(o)) records[r].erase("v"), records[r].erase("a");  // differentiated from the new x
    if (sampled_time) {
      std::vector<double> t(records[r].begin()->second.size());
      for (std::size_t k = 0; k < t.size(); ++k) t[k] = static_cast<double>(k) * *table.sampling_interval_s;
      records[r]["t"] = std::move(t);
    }
    Dataset d = dataset_from_columns(records[r], name, csv);
    d.source = table.source;
    for (auto& [variable, where] : d.operating_source)
      if (!d.operating_signals.count(variable)) where = "column mean";
    out.push_back(std::move(d));
  }
  return out;
}

namespace {

/// A plain record file (csv_loader.hpp) with the preprocessing options applied; v and a are differentiated again
/// from the preprocessed x.
Dataset preprocessed_csv(const RecordOptions& o, bool require_force) {
  CsvOptions csv;
  csv.require_force = require_force;
  if (!o.units.empty()) csv.units = parse_units_option(o.units);
  if (!o.columns.empty()) csv.columns = split_list(o.columns, "--columns");
  Dataset d = load_csv(o.path, csv);
  if (!wants_preprocessing(o) || d.is_system()) return d;
  Columns c{{"t", d.t_s}, {"x", d.x_m}};
  if (d.has_force()) c["F"] = d.F_N;
  for (const auto& [name, column] : d.operating_signals) c[name] = column;  // cut with the record (--whole-cycles)
  preprocess(c, o, o.path, false);
  d.t_s = c["t"];
  d.x_m = c["x"];
  if (d.has_force()) d.F_N = c["F"];
  for (auto& [name, column] : d.operating_signals) column = c[name];
  d.v_m_s = differentiate_3rd_order(d.t_s, d.x_m);
  d.a_m_s2 = differentiate_3rd_order(d.t_s, d.v_m_s);
  return d;
}

}  // namespace

std::vector<Dataset> read_record_file(const RecordOptions& o, bool require_force) {
  if (is_mat_path(o.path)) return records_from_channels(read_mat_file(o.path), o, require_force);
  const bool channels = is_column_map(o.columns) || o.skip_header >= 0 || !o.split.empty() || !o.scale.empty() ||
                        has_header_block(o.path);
  if (channels)
    return records_from_channels(read_text_channels(o.path, o.skip_header >= 0 ? std::optional<int>(o.skip_header)
                                                                             : std::nullopt),
                              o, require_force);
  return {preprocessed_csv(o, require_force)};
}

std::vector<std::string> operating_per_record(const std::string& text, std::size_t records, std::string_view option) {
  if (trim(text).empty()) return std::vector<std::string>(records);
  std::vector<std::pair<std::string, std::vector<std::string>>> lists;
  for (const auto& entry : split_list(text, option)) {
    const std::size_t equals = entry.find('=');
    if (equals == std::string::npos) {
      if (lists.empty()) throw InputError(fmt::format("{}: expected name=value, got '{}'", option, entry));
      lists.back().second.push_back(entry);
    } else {
      lists.push_back({std::string(trim(entry.substr(0, equals))), {std::string(trim(entry.substr(equals + 1)))}});
    }
  }
  std::vector<std::string> per_record(records);
  for (const auto& [name, values] : lists) {
    if (values.size() != 1 && values.size() != records)
      throw InputError(fmt::format("{} {}: {} values for {} record{} (give one value, or one per record in the file's "
                                   "order)",
                                   option, name, values.size(), records, records == 1 ? "" : "s"));
    for (std::size_t r = 0; r < records; ++r)
      per_record[r] += fmt::format("{}{}={}", per_record[r].empty() ? "" : ",", name, values[values.size() == 1 ? 0 : r]);
  }
  return per_record;
}

}  // namespace dampbench
