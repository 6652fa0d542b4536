#pragma once
// A rig's text export read as channels: an optional header block ("Header Size: 7", "Sampling Interval: 0.001",
// ..., its last line the column names), then one row per sample. Numeric columns become channels under their
// header names; text columns (a date-time stamp) are left out and named in messages; a column named Events keeps
// each row's events ("DAQ Pause", "DAQ Resume") for --split. An empty or "NaN" cell is NaN.
#include <istream>
#include <optional>
#include <string>

#include "engine/record/channel_table.hpp"

namespace dampbench {

/// Reads `path` (comma- or whitespace-separated). skip_header: the lines before the column names; nullopt detects a
/// header block whose first line is "Header Size: N" (N lines, the names last) and reads "Sampling Interval: dt" in
/// it. Throws InputError naming the file and line: a block of another shape, a row with more cells than names.
ChannelTable read_text_channels(const std::string& path, std::optional<int> skip_header);
ChannelTable parse_text_channels(std::istream& in, const std::string& source, std::optional<int> skip_header);

/// True when the file's first line opens a header block ("Header Size: N").
bool has_header_block(const std::string& path);

}  // namespace dampbench
