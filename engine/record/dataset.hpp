#pragma once
// A test record in SI units: structure-of-arrays signals plus the operating variables of the test.
#include <map>
#include <string>
#include <vector>

namespace dampbench {

/// One measured (or synthetic) test in SI units. A rig record (columns t, x, F): displacement in, force out; rotary
/// devices store the angle in x [rad] and the torque in F [N·m]. A system record (columns t, y, u): a structure
/// driven by the force u, its displacement y out; x, v, a and F are empty.
struct Dataset {
  std::string name;            ///< label used in tables (file stem by default)
  std::string source;          ///< file path or generator description
  std::vector<double> t_s;     ///< time [s], strictly increasing
  std::vector<double> x_m;     ///< displacement [m]
  std::vector<double> v_m_s;   ///< velocity [m/s] (from the file or 3rd-order differentiation)
  std::vector<double> a_m_s2;  ///< acceleration [m/s²] (from the file or 3rd-order differentiation)
  std::vector<double> F_N;     ///< measured force [N]; empty when only the input is known
  std::vector<double> u_N;     ///< system record: input force [N]
  std::vector<double> y_m;     ///< system record: measured displacement [m]; empty when only the input is known
  /// System record: u is one period of a periodic input, and y the steady response to it (evaluate --periodic).
  /// Otherwise the structure starts from rest at the first sample.
  bool periodic_input = false;
  /// Operating variables of the test (I [A], V [V], phi [deg], amp [m], freq [Hz]).
  std::map<std::string, double> operating;
  /// Where each operating variable comes from: "file comment", "column mean", "file name", "--set", "sine
  /// excitation" (none for a dataset built in code). The output and the model file show it beside the value.
  std::map<std::string, std::string> operating_source;
  /// Operating variables the record holds but cannot give as one constant, with why (a column that varies over
  /// the test): a law that needs one refuses the record with this text rather than use the column's mean.
  std::map<std::string, std::string> operating_refused;
  /// The columns of those variables, sample by sample (a value stated by the file, --conditions or --set replaces
  /// one): a law model follows them, stepped sample by sample (engine/model/stepped_simulation.hpp).
  std::map<std::string, std::vector<double>> operating_signals;

  [[nodiscard]] std::size_t size() const { return t_s.size(); }
  [[nodiscard]] bool has_force() const { return !F_N.empty(); }
  [[nodiscard]] bool is_system() const { return !u_N.empty(); }
  /// The measured output a model is compared with: y of a system record, F of a rig record.
  [[nodiscard]] const std::vector<double>& measured() const { return is_system() ? y_m : F_N; }
  [[nodiscard]] bool has_measured() const { return !measured().empty(); }
};

}  // namespace dampbench
