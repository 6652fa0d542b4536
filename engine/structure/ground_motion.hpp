#pragma once
// A ground-acceleration record for a building (../shared/data/earthquakes: El Centro, Kobe, Maule): CSV with a
// header naming t [s] and ag [m/s²], scaled by a factor before use (the UTFSM study scales its records).
#include <string>
#include <vector>

namespace dampbench::structure {

struct GroundMotion {
  std::string name;              ///< the file's stem
  std::vector<double> t_s;       ///< strictly increasing
  std::vector<double> ag_m_s2;   ///< ground acceleration, scaled

  /// ag at time t, linear between the samples (the last value past the end).
  [[nodiscard]] double at(double t) const;
  [[nodiscard]] double duration_s() const { return t_s.empty() ? 0.0 : t_s.back() - t_s.front(); }
};

/// Reads columns t and ag of a CSV file with a header and multiplies ag by `scale`. InputError naming the file,
/// the line and what was expected: a missing column, a field that is not a number, times not increasing, fewer
/// than two samples, a scale that is not a finite number.
GroundMotion read_ground_motion(const std::string& path, double scale);

}  // namespace dampbench::structure
