#include "engine/record/text_channels.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/record/csv_loader.hpp"

namespace dampbench {
namespace {

constexpr std::string_view kHeaderSize = "header size:";
constexpr std::string_view kSamplingInterval = "sampling interval:";

/// The value after "key:" on a header-block line, when the line starts with that key (case-insensitive).
std::optional<std::string_view> block_value(std::string_view line, std::string_view key) {
  if (lowercase(line.substr(0, key.size())) != key) return std::nullopt;
  return trim(line.substr(key.size()));
}

/// The header block's size in lines from its first line, when it has one.
std::optional<int> detected_block(const std::vector<std::string>& lines, const std::string& source) {
  if (lines.empty()) return std::nullopt;
  const auto size = block_value(trim(lines.front()), kHeaderSize);
  if (!size) return std::nullopt;
  const ParsedNumber n = try_parse_number(*size);
  if (n.status != NumberStatus::ok || n.value < 1 || n.value != std::floor(n.value) ||
      n.value > static_cast<double>(lines.size()))
    throw InputError(fmt::format("{}:1: a header block of another shape: expected 'Header Size: N' with N the block's "
                                 "lines (the column names last), got '{}'",
                                 source, trim(lines.front())));
  return static_cast<int>(n.value) - 1;  // the lines before the names line
}

}  // namespace

ChannelTable parse_text_channels(std::istream& in, const std::string& source, std::optional<int> skip_header) {
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (lines.empty() && line.starts_with("\xEF\xBB\xBF")) line.erase(0, 3);
    lines.push_back(std::move(line));
  }
  ChannelTable table;
  table.source = source;
  const std::optional<int> block = skip_header ? skip_header : detected_block(lines, source);
  std::size_t names_line = static_cast<std::size_t>(block.value_or(0));
  if (!block)  // a plain record file's leading comments and blank lines, as csv_loader.hpp skips them
    while (names_line < lines.size() && (trim(lines[names_line]).empty() || trim(lines[names_line]).front() == '#'))
      ++names_line;
  if (skip_header && *skip_header < 0) throw InputError(fmt::format("{}: --skip-header: expected 0 or more lines", source));
  if (names_line >= lines.size())
    throw InputError(fmt::format("{}: the file has {} lines; the column names were expected on line {}", source,
                                 lines.size(), names_line + 1));
  for (std::size_t i = 0; i < names_line; ++i)
    if (const auto dt = block_value(trim(lines[i]), kSamplingInterval)) {
      const ParsedNumber n = try_parse_number(*dt);
      if (n.status != NumberStatus::ok || !(n.value > 0) || !std::isfinite(n.value))
        throw InputError(fmt::format("{}:{}: expected a sampling interval in seconds, got '{}'", source, i + 1, *dt));
      table.sampling_interval_s = n.value;
    }
  const std::string_view names_text = trim(lines[names_line]);
  if (block && !skip_header && names_text.find(',') == std::string_view::npos &&
      names_text.find(": ") != std::string_view::npos)  // a "Key:  value" line of the block, not the names
    throw InputError(fmt::format("{}:{}: a header block of another shape: 'Header Size: {}' puts the column names on "
                                 "line {}, which reads '{}' (give the lines before the names with --skip-header)",
                                 source, names_line + 1, *block + 1, names_line + 1, names_text));
  const bool comma = names_text.find(',') != std::string_view::npos;
  const auto names = split_cells(names_text, comma);
  if (std::all_of(names.begin(), names.end(),
                  [](std::string_view c) { return try_parse_number(c).status == NumberStatus::ok; }))
    throw InputError(fmt::format("{}:{}: expected the column names, got numbers ('{}'){}", source, names_line + 1,
                                 names_text, block ? ": a header block of another shape" : ""));
  std::vector<std::vector<std::string>> cells(names.size());
  std::vector<std::size_t> row_lines;
  for (std::size_t i = names_line + 1; i < lines.size(); ++i) {
    const std::string_view text = trim(lines[i]);
    if (text.empty() || text.front() == '#') continue;
    const auto row = split_cells(text, comma);
    if (row.size() > names.size())
      throw InputError(fmt::format("{}:{}: {} cells, but line {} names {} columns{}", source, i + 1, row.size(),
                                   names_line + 1, names.size(),
                                   block && !skip_header ? " (a header block of another shape? 'Header Size: N' "
                                                           "counts the block's lines, the column names last)"
                                                         : ""));
    for (std::size_t c = 0; c < names.size(); ++c) cells[c].emplace_back(c < row.size() ? row[c] : std::string_view{});
    row_lines.push_back(i + 1);
  }
  for (std::size_t c = 0; c < names.size(); ++c) {
    const std::string name(names[c]);
    if (const std::string lower = lowercase(name); lower == "events" || lower == "event") {
      table.events = cells[c];
      continue;
    }
    Channel channel{cells[c].size(), 1, {}};
    bool numeric = true;
    for (const std::string& cell : cells[c]) {
      const ParsedNumber n = try_parse_number(cell);
      if (n.status == NumberStatus::ok) channel.values.push_back(n.value);  // "nan" included
      else if (cell.empty() || lowercase(cell) == "nan") channel.values.push_back(std::numeric_limits<double>::quiet_NaN());
      else { numeric = false; break; }
    }
    if (!numeric) {
      table.skipped.push_back(name + " (text)");
      continue;
    }
    if (table.channels.count(name))
      throw InputError(fmt::format("{}:{}: column '{}' named twice", source, names_line + 1, name));
    table.names.push_back(name);
    table.channels.emplace(name, std::move(channel));
  }
  if (row_lines.empty()) throw InputError(fmt::format("{}: no data rows after the column names (line {})", source, names_line + 1));
  return table;
}

ChannelTable read_text_channels(const std::string& path, std::optional<int> skip_header) {
  std::ifstream file(path);
  if (!file) throw InputError(fmt::format("cannot open data file '{}'", path));
  return parse_text_channels(file, path, skip_header);
}

bool has_header_block(const std::string& path) {
  std::ifstream file(path);
  std::string first;
  if (!file || !std::getline(file, first)) return false;
  if (first.starts_with("\xEF\xBB\xBF")) first.erase(0, 3);
  return block_value(trim(first), kHeaderSize).has_value();
}

}  // namespace dampbench
