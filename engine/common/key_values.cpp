#include "engine/common/key_values.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <system_error>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {
namespace {

/// Splits at every comma; each piece is trimmed. "" gives one empty piece.
std::vector<std::string_view> split_commas(std::string_view text) {
  std::vector<std::string_view> pieces;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    pieces.push_back(
        trim(text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) return pieces;
    start = comma + 1;
  }
}

}  // namespace

std::string_view trim(std::string_view text) {
  constexpr std::string_view blanks = " \t\r\n\v\f";
  const std::size_t first = text.find_first_not_of(blanks);
  if (first == std::string_view::npos) return {};
  const std::size_t last = text.find_last_not_of(blanks);
  return text.substr(first, last - first + 1);
}

std::string lowercase(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

ParsedNumber try_parse_number(std::string_view text) {
  // from_chars rejects a leading '+'; allow exactly one, not followed by a sign.
  if (!text.empty() && text.front() == '+') {
    text.remove_prefix(1);
    if (!text.empty() && (text.front() == '+' || text.front() == '-')) return {};
  }
  if (text.empty()) return {};
  ParsedNumber parsed;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, parsed.value);
  if (ptr != end) return {};  // trailing characters, or nothing parsed at all
  if (ec == std::errc::result_out_of_range)
    parsed.status = NumberStatus::out_of_range;
  else if (ec == std::errc())
    parsed.status = NumberStatus::ok;
  return parsed;
}

std::vector<std::pair<std::string, std::string>> parse_key_values(std::string_view text, std::string_view option) {
  std::vector<std::pair<std::string, std::string>> entries;
  if (trim(text).empty()) return entries;
  for (const std::string_view piece : split_commas(text)) {
    const std::size_t equals = piece.find('=');
    if (equals == std::string_view::npos || trim(piece.substr(equals + 1)).empty())
      throw InputError(fmt::format("{}: expected name=value, got '{}'", option, piece));
    const std::string name(trim(piece.substr(0, equals)));
    if (name.empty()) throw InputError(fmt::format("{}: empty name in '{}'", option, piece));
    for (const auto& entry : entries)
      if (entry.first == name) throw InputError(fmt::format("{}: '{}' given twice", option, name));
    entries.emplace_back(name, std::string(trim(piece.substr(equals + 1))));
  }
  return entries;
}

double parse_number(std::string_view text, std::string_view what) {
  const ParsedNumber parsed = try_parse_number(text);
  if (parsed.status == NumberStatus::out_of_range)
    throw InputError(fmt::format("{}: number out of range, got '{}'", what, text));
  if (parsed.status != NumberStatus::ok) throw InputError(fmt::format("{}: expected a number, got '{}'", what, text));
  if (!std::isfinite(parsed.value)) throw InputError(fmt::format("{}: expected a finite number, got '{}'", what, text));
  return parsed.value;
}

std::vector<std::string> split_list(std::string_view text, std::string_view option) {
  std::vector<std::string> names;
  for (const std::string_view piece : split_commas(text)) {
    if (piece.empty()) throw InputError(fmt::format("{}: empty entry in '{}'", option, text));
    names.emplace_back(piece);
  }
  return names;
}

}  // namespace dampbench
