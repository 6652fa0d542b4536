#pragma once
// An optimizer's number settings as one typed table (key, field, allowed values, one-line meaning), so that one
// table reads the "key" → "value" strings of --optimizer-settings and sweep files (registry.cpp), checks the ranges
// (each Settings::validate()) and lists every setting with its default (`dampbench optimizers`, the guide's table).
// Defaults live once, in the Settings structs. Settings that pick a name (pso's variant, de's strategy, cmaes's
// restarts, a hybrid's global stage) are ChoiceSetting rows: listed here, read by the registry.
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/common/error.hpp"

namespace dampbench {

/// The numbers a setting allows: from `lower` to `upper`, each end open or closed; whole numbers when `whole`.
struct SettingRange {
  double lower = 0, upper = std::numeric_limits<double>::infinity();
  bool lower_open = false, upper_open = false, whole = false;

  [[nodiscard]] bool contains(double v) const {
    if (!std::isfinite(v)) return false;
    return (lower_open ? v > lower : v >= lower) && (upper_open ? v < upper : v <= upper);
  }
  /// As messages and the guide say it: "in [0, 1]", "in (0, 0.1]", "a finite number >= 0", "a finite number > 0",
  /// "at least 1", "0 or 1".
  [[nodiscard]] std::string text() const {
    if (whole && !std::isfinite(upper)) return fmt::format("at least {:g}", lower);
    if (whole && upper == lower + 1) return fmt::format("{:g} or {:g}", lower, upper);
    if (!std::isfinite(upper)) return fmt::format("a finite number {} {:g}", lower_open ? ">" : ">=", lower);
    return fmt::format("in {}{:g}, {:g}{}", lower_open ? "(" : "[", lower, upper, upper_open ? ")" : "]");
  }
};

inline constexpr SettingRange kProbability{0, 1};                                        // [0, 1]
inline constexpr SettingRange kNonNegative{};                                            // finite, >= 0
inline constexpr SettingRange kPositive{0, std::numeric_limits<double>::infinity(), true};  // finite, > 0
inline constexpr SettingRange kFdStep{0, 0.1, true};                                     // (0, 0.1]
inline constexpr SettingRange whole_at_least(double n) {
  return {n, std::numeric_limits<double>::infinity(), false, false, true};
}

/// One number setting of the Settings struct S.
template <class S>
struct NumberSetting {
  std::string_view key;
  std::variant<double S::*, std::optional<double> S::*, int S::*, std::optional<int> S::*> field;
  SettingRange range;
  std::string_view meaning;
  std::string_view unset = {};  ///< an optional field's rule when it is not given ("1/d for d parameters")
};

template <class S>
using SettingTable = std::vector<NumberSetting<S>>;

/// The rows of a base struct's table as rows of a struct derived from it.
template <class Derived, class Base>
SettingTable<Derived> rebased(const SettingTable<Base>& rows) {
  SettingTable<Derived> out;
  for (const auto& row : rows)
    out.push_back({row.key,
                   std::visit([](auto field) -> decltype(NumberSetting<Derived>::field) { return field; }, row.field),
                   row.range, row.meaning, row.unset});
  return out;
}

/// The table's rows followed by `more`'s.
template <class S>
SettingTable<S> joined(SettingTable<S> rows, const SettingTable<S>& more) {
  rows.insert(rows.end(), more.begin(), more.end());
  return rows;
}

/// The value of a row's field in `s` (nullopt for an optional field left unset).
template <class S>
std::optional<double> setting_value(const NumberSetting<S>& row, const S& s) {
  return std::visit(
      [&](auto field) -> std::optional<double> {
        const auto& v = s.*field;
        if constexpr (requires { v.has_value(); }) {
          if (!v) return std::nullopt;
          return static_cast<double>(*v);
        } else {
          return static_cast<double>(v);
        }
      },
      row.field);
}

/// InputError "{optimizer}: {key} must be {range}, got {value}" for the first field of `s` outside its range.
template <class S>
void check_ranges(std::string_view optimizer, const SettingTable<S>& table, const S& s) {
  for (const auto& row : table)
    if (const auto v = setting_value(row, s); v && !row.range.contains(*v))
      throw InputError(fmt::format("{}: {} must be {}, got {:g}", optimizer, row.key, row.range.text(), *v));
}

/// A setting that picks one of `names`.
struct ChoiceSetting {
  std::string_view key;
  std::vector<std::string_view> names;
  std::string_view default_name, meaning;
};

/// A row of `dampbench optimizers`: key, type, default, allowed values, meaning.
struct SettingRow {
  std::string key, type, default_value, allowed, meaning;
};

/// The table's rows as listed, with the defaults of `defaults`.
template <class S>
std::vector<SettingRow> listed(const SettingTable<S>& table, const S& defaults) {
  std::vector<SettingRow> rows;
  for (const auto& row : table) {
    const auto v = setting_value(row, defaults);
    rows.push_back({std::string(row.key), row.range.whole ? "whole number" : "number",
                    v ? fmt::format("{:g}", *v) : std::string(row.unset), row.range.text(), std::string(row.meaning)});
  }
  return rows;
}

inline SettingRow listed(const ChoiceSetting& c) {
  return {std::string(c.key), "choice", std::string(c.default_name), fmt::format("{}", fmt::join(c.names, ", ")),
          std::string(c.meaning)};
}

}  // namespace dampbench
