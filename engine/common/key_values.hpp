#pragma once
// Small parsers for command-line values: "name=value" lists, strict numbers, comma-separated names.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dampbench {

/// Outcome of a non-throwing number parse (see try_parse_number).
enum class NumberStatus { ok, not_a_number, out_of_range };

/// A parsed number; `value` is meaningful only when status == ok (it may then be NaN or ±Inf).
struct ParsedNumber {
  double value = 0;
  NumberStatus status = NumberStatus::not_a_number;
};

/// Text without leading and trailing whitespace (spaces, tabs, CR, LF).
std::string_view trim(std::string_view text);

/// `text` in lower case (ASCII letters; other bytes as they are), for names compared without regard to case.
std::string lowercase(std::string_view text);

/// Parses a whole string as a double with std::from_chars (locale-free). Accepts exponents and one leading
/// '+'; "nan" and "inf" parse (non-finite value, status ok). No surrounding whitespace is allowed.
ParsedNumber try_parse_number(std::string_view text);

/// Parses "name=value,name=value" (as in --params, --units, --sine, --bounds). `option` names the
/// source for messages (e.g. "--params"). Keeps order; rejects empty names, missing '=', duplicates.
/// Names and values are trimmed; an empty (or all-blank) text gives an empty list.
std::vector<std::pair<std::string, std::string>> parse_key_values(std::string_view text, std::string_view option);

/// Strict number parse of a whole string (std::from_chars; rejects "", "1.2x", "nan", "inf"); message names `what`.
double parse_number(std::string_view text, std::string_view what);

/// Splits "t,x,v,F" into trimmed names (rejects empty entries).
std::vector<std::string> split_list(std::string_view text, std::string_view option);

}  // namespace dampbench
