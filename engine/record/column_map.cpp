#include "engine/record/column_map.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/record/units.hpp"

namespace dampbench {
namespace {

/// The whole number ≥ 0 that `text` writes (up to 2^53, where a double still holds every integer); nullopt for
/// anything else, "inf" and "nan" included.
std::optional<std::size_t> whole_number(std::string_view text) {
  const ParsedNumber n = try_parse_number(trim(text));
  if (n.status != NumberStatus::ok || !(n.value >= 0) || n.value > 9007199254740992.0 || n.value != std::floor(n.value))
    return std::nullopt;
  return static_cast<std::size_t>(n.value);
}

/// Entries of a comma-separated list, a comma inside [...] not separating.
std::vector<std::string_view> split_outside_brackets(std::string_view text) {
  std::vector<std::string_view> entries;
  int depth = 0;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    if (i == text.size() || (text[i] == ',' && depth == 0)) {
      entries.push_back(trim(text.substr(start, i - start)));
      start = i + 1;
    } else if (text[i] == '[') {
      ++depth;
    } else if (text[i] == ']') {
      --depth;
    }
  }
  return entries;
}

/// "k" → [k, k+1); "a:b" → [a, b), range. Throws InputError(`what`) when not whole numbers with a < b.
void parse_index(std::string_view text, ColumnPick& pick, const std::string& what) {
  const auto whole = [&](std::string_view s) {
    const auto k = whole_number(s);
    if (!k) throw InputError(fmt::format("{}: expected an index counted from 0, got '{}'", what, trim(s)));
    return *k;
  };
  if (const std::size_t colon = text.find(':'); colon != std::string_view::npos) {
    pick.first = whole(text.substr(0, colon));
    pick.last = whole(text.substr(colon + 1));
    pick.range = true;
    if (pick.last <= pick.first)
      throw InputError(fmt::format("{}: the range {} is empty (a:b takes a, a+1, ..., b-1)", what, trim(text)));
  } else {
    pick.first = whole(text);
    pick.last = pick.first + 1;
  }
}

ColumnPick parse_pick(std::string_view entry, std::string_view option) {
  const std::string what = fmt::format("{} '{}'", option, entry);
  const std::size_t equals = entry.find('=');
  if (equals == std::string_view::npos)
    throw InputError(fmt::format("{}: expected column=source (e.g. x=data[:,0]); a mapping gives every column so", what));
  ColumnPick pick;
  pick.text = std::string(entry);
  pick.column = std::string(trim(entry.substr(0, equals)));
  if (!is_known_column(pick.column))
    throw InputError(fmt::format("{}: unknown record column '{}' (known: {})", what, pick.column, known_columns_text()));
  std::string_view source = trim(entry.substr(equals + 1));
  const std::size_t bracket = source.find('[');
  if (bracket == std::string_view::npos) {
    pick.channel = std::string(source);
  } else {
    if (source.back() != ']') throw InputError(fmt::format("{}: expected name[:,k] or name[k,:], got '{}'", what, source));
    pick.channel = std::string(trim(source.substr(0, bracket)));
    const std::string_view inside = source.substr(bracket + 1, source.size() - bracket - 2);
    const std::size_t comma = inside.find(',');
    if (comma == std::string_view::npos)
      throw InputError(fmt::format("{}: expected two indices, name[:,k] (column k) or name[k,:] (row k)", what));
    const std::string_view rows = trim(inside.substr(0, comma)), cols = trim(inside.substr(comma + 1));
    if (rows == ":" && cols != ":") {
      pick.axis = ColumnPick::Axis::column;
      parse_index(cols, pick, what);
    } else if (cols == ":" && rows != ":") {
      pick.axis = ColumnPick::Axis::row;
      parse_index(rows, pick, what);
    } else {
      throw InputError(fmt::format("{}: expected name[:,k] (column k) or name[k,:] (row k), one of them ':'", what));
    }
  }
  if (pick.channel.empty()) throw InputError(fmt::format("{}: no channel name after '='", what));
  return pick;
}

}  // namespace

std::string channel_list(const ChannelTable& table) {
  std::string list;
  for (const auto& name : table.names) {
    const Channel& c = table.channels.at(name);
    list += fmt::format("{}{} ({}x{})", list.empty() ? "" : ", ", name, c.rows, c.cols);
  }
  for (const auto& name : table.skipped) list += fmt::format("{}{}", list.empty() ? "" : ", ", name);
  return list.empty() ? "nothing" : list;
}

bool is_column_map(std::string_view text) { return text.find('=') != std::string_view::npos; }

std::vector<ColumnPick> parse_column_map(std::string_view text, std::string_view option) {
  std::vector<ColumnPick> picks;
  for (std::string_view entry : split_outside_brackets(text)) {
    if (entry.empty()) throw InputError(fmt::format("{}: an empty entry in '{}'", option, text));
    picks.push_back(parse_pick(entry, option));
    for (std::size_t i = 0; i + 1 < picks.size(); ++i)
      if (picks[i].column == picks.back().column)
        throw InputError(fmt::format("{}: column '{}' given twice ('{}' and '{}')", option, picks.back().column,
                                     picks[i].text, picks.back().text));
  }
  return picks;
}

namespace {

/// The element k of "s(k)<suffix>" that `channel` names, or 0.
std::size_t element_of(std::string_view channel, std::string_view prefix, std::string_view suffix) {
  if (!channel.starts_with(prefix) || channel.size() <= prefix.size() + 2 || channel[prefix.size()] != '(') return 0;
  const std::size_t close = channel.find(')', prefix.size());
  if (close == std::string_view::npos || channel.substr(close + 1, suffix.size()) != suffix) return 0;
  const std::string_view rest = channel.substr(close + 1 + suffix.size());
  if (!rest.empty() && !rest.starts_with(" (")) return 0;  // a skipped entry: "s(2).x (empty)"
  return whole_number(channel.substr(prefix.size() + 1, close - prefix.size() - 1)).value_or(0);  // 0: not s(k)
}

/// "s(:).x": the channels s(1).x, s(2).x, ... of every element (one element: "s.x", as mat_file.hpp names it). An
/// element without that numeric field is an error naming it, never a record silently left out.
std::vector<std::string> element_names(const ChannelTable& table, const ColumnPick& pick, std::size_t all) {
  const std::string prefix = pick.channel.substr(0, all), suffix = pick.channel.substr(all + 3);
  std::map<std::size_t, std::string> present;
  std::size_t last = 0;
  for (const auto& name : table.names)
    if (const std::size_t k = element_of(name, prefix, suffix)) present[k] = name, last = std::max(last, k);
  std::map<std::size_t, std::string> skipped;
  for (const auto& entry : table.skipped)
    if (const std::size_t k = element_of(entry, prefix, suffix)) skipped[k] = entry, last = std::max(last, k);
  if (last == 0) {
    if (table.channels.count(prefix + suffix)) return {prefix + suffix};
    throw InputError(fmt::format("{}: --columns '{}': no channel '{}(k){}' for k = 1, 2, ... in the file (it holds: {})",
                                 table.source, pick.text, prefix, suffix, channel_list(table)));
  }
  std::vector<std::string> names;
  for (std::size_t k = 1; k <= last; ++k) {
    if (!present.count(k))
      throw InputError(fmt::format("{}: --columns '{}': element {} has no numeric '{}({}){}'{}", table.source, pick.text,
                                   k, prefix, k, suffix, skipped.count(k) ? fmt::format(" ({})", skipped[k]) : ""));
    names.push_back(present[k]);
  }
  return names;
}

/// The channel names a pick's source stands for: "#k" → the file's k-th numeric channel; "s(:).x" → "s(1).x",
/// "s(2).x", ... as far as they go (a struct array's elements: engine/record/mat_file.hpp); else the name itself.
std::vector<std::string> channel_names(const ChannelTable& table, const ColumnPick& pick) {
  const std::string& name = pick.channel;
  if (name.starts_with('#')) {  // the file's k-th column, counted from 0
    const auto k = whole_number(name.substr(1));
    if (!k) throw InputError(fmt::format("{}: --columns '{}': expected #k with k counted from 0", table.source, pick.text));
    if (*k >= table.names.size())
      throw InputError(fmt::format("{}: --columns '{}': the file has {} numeric columns ({})", table.source, pick.text,
                                   table.names.size(), channel_list(table)));
    return {table.names[*k]};
  }
  if (const std::size_t all = name.find("(:)"); all != std::string::npos) return element_names(table, pick, all);
  if (!table.channels.count(name))
    throw InputError(fmt::format("{}: --columns '{}': no channel '{}' in the file (it holds: {})", table.source,
                                 pick.text, name, channel_list(table)));
  return {name};
}

}  // namespace

std::vector<std::vector<double>> pick_vectors(const ChannelTable& table, const ColumnPick& pick) {
  const std::vector<std::string> names = channel_names(table, pick);
  if (names.size() > 1 && pick.range)
    throw InputError(fmt::format("{}: --columns '{}': an index range and (:) both make several records; use one",
                                 table.source, pick.text));
  std::vector<std::vector<double>> out;
  for (const std::string& name : names) {
    const Channel& c = table.channels.at(name);
    if (pick.axis == ColumnPick::Axis::whole) {
      if (c.rows != 1 && c.cols != 1)
        throw InputError(fmt::format("{}: --columns '{}': '{}' is a {}x{} matrix; pick a column ({}[:,k]) or a row ({}[k,:])",
                                     table.source, pick.text, name, c.rows, c.cols, name, name));
      out.push_back(c.values);
      continue;
    }
    const bool by_column = pick.axis == ColumnPick::Axis::column;
    const std::size_t count = by_column ? c.cols : c.rows;
    if (pick.last > count)
      throw InputError(fmt::format("{}: --columns '{}': {} {} out of range: '{}' is {}x{} ({} counted from 0)",
                                   table.source, pick.text, by_column ? "column" : "row", pick.last - 1, name, c.rows,
                                   c.cols, by_column ? "columns" : "rows"));
    for (std::size_t k = pick.first; k < pick.last; ++k) {
      std::vector<double> v;
      if (by_column) {
        v.assign(c.values.begin() + static_cast<std::ptrdiff_t>(k * c.rows),
                 c.values.begin() + static_cast<std::ptrdiff_t>((k + 1) * c.rows));
      } else {
        v.reserve(c.cols);
        for (std::size_t j = 0; j < c.cols; ++j) v.push_back(c.at(k, j));
      }
      out.push_back(std::move(v));
    }
  }
  return out;
}

}  // namespace dampbench
