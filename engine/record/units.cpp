#include "engine/record/units.hpp"

#include <array>
#include <numbers>
#include <span>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"

namespace dampbench {
namespace {

struct Unit {
  std::string_view name;
  double factor;  ///< value_SI = value * factor
};

struct Column {
  std::string_view name;
  std::span<const Unit> units;  ///< first entry is the SI unit
};

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kInch = 0.0254;                 // m, exact
constexpr double kPoundForce = 4.4482216152605;  // N, exact (0.45359237 kg × 9.80665 m/s²)
constexpr double kStandardGravity = 9.80665;     // m/s², exact

constexpr std::array<Unit, 2> kTime{{{"s", 1.0}, {"ms", 1e-3}}};
constexpr std::array<Unit, 7> kDisplacement{
    {{"m", 1.0}, {"mm", 1e-3}, {"cm", 1e-2}, {"um", 1e-6}, {"in", kInch}, {"rad", 1.0}, {"deg", kDeg}}};
constexpr std::array<Unit, 6> kVelocity{
    {{"m/s", 1.0}, {"mm/s", 1e-3}, {"cm/s", 1e-2}, {"in/s", kInch}, {"rad/s", 1.0}, {"deg/s", kDeg}}};
constexpr std::array<Unit, 4> kAcceleration{
    {{"m/s^2", 1.0}, {"mm/s^2", 1e-3}, {"g", kStandardGravity}, {"rad/s^2", 1.0}}};
constexpr std::array<Unit, 8> kForce{{{"N", 1.0},
                                      {"kN", 1e3},
                                      {"lbf", kPoundForce},
                                      {"kip", 1e3 * kPoundForce},
                                      {"N*m", 1.0},
                                      {"N.m", 1.0},
                                      {"Nm", 1.0},
                                      {"kN*m", 1e3}}};
constexpr std::array<Unit, 2> kCurrent{{{"A", 1.0}, {"mA", 1e-3}}};
constexpr std::array<Unit, 2> kVoltage{{{"V", 1.0}, {"mV", 1e-3}}};
constexpr std::array<Unit, 2> kAngle{{{"deg", 1.0}, {"rad", 1.0 / kDeg}}};  // phi is kept in degrees

constexpr std::array<Column, 10> kColumns{{{"t", kTime},
                                           {"x", kDisplacement},
                                           {"v", kVelocity},
                                           {"a", kAcceleration},
                                           {"F", kForce},
                                           {"y", kDisplacement},
                                           {"u", kForce},
                                           {"I", kCurrent},
                                           {"V", kVoltage},
                                           {"phi", kAngle}}};

const Column* find_column(std::string_view name) {
  for (const Column& column : kColumns)
    if (column.name == name) return &column;
  return nullptr;
}

std::string unit_names(const Column& column) {
  std::string names;
  for (const Unit& unit : column.units) names += (names.empty() ? "" : ", ") + std::string(unit.name);
  return names;
}

}  // namespace

bool is_known_column(std::string_view column) { return find_column(column) != nullptr; }

std::string known_columns_text() {
  std::string names;
  for (const Column& column : kColumns) names += (names.empty() ? "" : ", ") + std::string(column.name);
  return names;
}

double unit_to_si(std::string_view column, std::string_view unit) {
  const Column* entry = find_column(column);
  if (entry == nullptr) throw InputError(fmt::format("unknown column '{}' (known: {})", column, known_columns_text()));
  for (const Unit& candidate : entry->units)
    if (candidate.name == unit) return candidate.factor;
  throw InputError(fmt::format("unknown unit '{}' for column '{}' (known: {})", unit, column, unit_names(*entry)));
}

std::pair<std::string, std::string> split_name_unit(std::string_view cell) {
  const std::size_t open = cell.find('[');
  const std::size_t close = cell.find(']');
  if (open == std::string_view::npos && close == std::string_view::npos) return {std::string(trim(cell)), ""};
  if (open == std::string_view::npos || close == std::string_view::npos || close < open ||
      !trim(cell.substr(close + 1)).empty())
    throw InputError(fmt::format("header cell '{}': expected name or name[unit], e.g. x[mm]", cell));
  return {std::string(trim(cell.substr(0, open))), std::string(trim(cell.substr(open + 1, close - open - 1)))};
}

}  // namespace dampbench
