#pragma once
// Units of the columns of a test record and their factors to SI.
#include <string>
#include <string_view>
#include <utility>

namespace dampbench {

/// Factor that converts a value in `unit` of the column `column` to SI (value_SI = value * factor).
/// Columns and accepted units: t: s, ms; x: m, mm, cm, um, in, rad, deg (deg→rad for rotary angle records);
/// v: m/s, mm/s, cm/s, in/s, rad/s, deg/s; a: m/s^2, mm/s^2, g (9.80665), rad/s^2; F: N, kN, lbf, kip, N*m, N.m, Nm,
/// kN*m; y: as x; u: as F; I: A, mA; V: V, mV; phi: deg (phi stays in degrees: factor 1; "rad" converts to degrees). Unit names are
/// case-sensitive. Throws InputError (without a file prefix; callers add one): "unknown unit 'furlong' for column 'x'
/// (known: m, mm, cm, um, in, rad, deg)" and "unknown column 'q' (known: t, x, v, a, F, y, u, I, V, phi)".
double unit_to_si(std::string_view column, std::string_view unit);

/// True for the column names a record may have: t, x, v, a, F, y, u, I, V, phi.
bool is_known_column(std::string_view column);

/// "t, x, v, a, F, y, u, I, V, phi", for messages.
std::string known_columns_text();

/// Splits a header cell "x[mm]" or "x [mm]" or "x" into {name, unit} (unit empty when absent), both trimmed.
/// Throws InputError for an unclosed or misplaced bracket ("x[mm", "x]", "x[mm]y").
std::pair<std::string, std::string> split_name_unit(std::string_view cell);

}  // namespace dampbench
