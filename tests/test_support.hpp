#pragma once
// Helpers shared by the tests: synthetic records with analytic derivatives, and running the CLI.
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/common/random.hpp"
#include "engine/record/dataset.hpp"
#include "engine/common/error.hpp"
#include "engine/record/excitation.hpp"
#include "engine/record/signals.hpp"

namespace dampbench::testing {

/// An empty folder for the running test: <tmp>/dampbench_<prefix>_<test name> (emptied first).
inline std::filesystem::path test_temp_dir(const std::string& prefix) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("dampbench_" + prefix + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Writes `text` to p, creating p's folder.
inline void write_text(const std::filesystem::path& p, const std::string& text) {
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

/// The bits of a double, for tests that compare results bit for bit.
inline std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

/// Passes when `message` contains `expected`, and shows both when it does not.
inline ::testing::AssertionResult HasText(const std::string& message, const std::string& expected) {
  if (message.find(expected) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "message \"" << message << "\" lacks \"" << expected << "\"";
}

/// x = X1 sin(ω1 t) + X2 sin(ω2 t + φ) with exact v and a; no force. Two frequencies make the mass
/// identifiable: on a single sine m·a = −mω²x is indistinguishable from a negative stiffness.
inline Dataset two_sine_record(int samples = 1000, double fs_hz = 500.0) {
  Dataset d;
  d.name = "two_sine";
  const double X1 = 0.015, w1 = 2 * std::numbers::pi * 1.5, X2 = 0.006, w2 = 2 * std::numbers::pi * 4.1, phase = 0.3;
  for (int k = 0; k < samples; ++k) {
    const double t = k / fs_hz;
    d.t_s.push_back(t);
    d.x_m.push_back(X1 * std::sin(w1 * t) + X2 * std::sin(w2 * t + phase));
    d.v_m_s.push_back(X1 * w1 * std::cos(w1 * t) + X2 * w2 * std::cos(w2 * t + phase));
    d.a_m_s2.push_back(-X1 * w1 * w1 * std::sin(w1 * t) - X2 * w2 * w2 * std::sin(w2 * t + phase));
  }
  return d;
}

/// The input of a two-sine test for a model of either kind: two_sine_record's displacement for a rig model, a force
/// of the same shape (±84 N) for a system model (a t, u record).
inline Dataset two_sine_input(bool system, int samples = 1000, double fs_hz = 500.0) {
  Dataset d = two_sine_record(samples, fs_hz);
  if (!system) return d;
  Dataset s;
  s.name = d.name;
  s.t_s = d.t_s;
  for (double x : d.x_m) s.u_N.push_back(4000 * x);
  return s;
}

/// The measured output a model is compared with: F of a rig record, y of a system record.
inline std::vector<double>& measured_output(Dataset& d) { return d.is_system() ? d.y_m : d.F_N; }

/// Adds Gaussian noise of `relative` × RMS(d.F_N) to d.F_N from the keyed stream (seed); returns the RMS of the
/// noise actually added (the noise floor a fit can reach).
inline double add_force_noise(Dataset& d, double relative, std::uint64_t seed) {
  double rms = 0;
  for (double f : d.F_N) rms += f * f;
  rms = std::sqrt(rms / static_cast<double>(d.F_N.size()));
  RandomStream rng(hash_key({seed}));
  double added = 0;
  for (double& f : d.F_N) {
    const double e = relative * rms * rng.normal();
    f += e;
    added += e * e;
  }
  return std::sqrt(added / static_cast<double>(d.F_N.size()));
}

/// The message of the InputError that fn throws, or "no error".
template <class Fn>
std::string error_of(Fn&& fn) {
  try {
    fn();
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

/// Prepared signals of a sinusoid (engine/record/excitation.hpp) with the given operating variables.
inline Signals sine_signals(double amp_m, double freq_hz, double cycles, double fs_hz,
                            const std::map<std::string, double>& operating = {}) {
  SineSpec spec;
  spec.amplitude_m = amp_m;
  spec.freq_hz = freq_hz;
  spec.cycles = cycles;
  spec.fs_hz = fs_hz;
  Dataset d = make_sine(spec);
  for (const auto& [k, v] : operating) d.operating[k] = v;
  return prepare_signals(d);
}

struct CommandResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together (run_dampbench), or stdout alone (run_dampbench_json)
  std::string errors;  ///< stderr, when run_dampbench_json keeps it apart
};

/// Runs a shell command; its stdout in `output`.
inline CommandResult run_shell(const std::string& cmd) {
  CommandResult r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe)) r.output += buf.data();
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// Runs the dampbench executable with the given argument string (shell syntax).
inline CommandResult run_dampbench(const std::string& args) {
  return run_shell(std::string(DAMPBENCH_EXE) + " " + args + " 2>&1");
}

/// Runs dampbench for an output to parse (--format json): stdout in `output`, stderr (progress lines, messages)
/// apart in `errors`.
inline CommandResult run_dampbench_json(const std::string& args) {
  const auto err = test_temp_dir("stderr") / "stderr.txt";
  CommandResult r = run_shell(std::string(DAMPBENCH_EXE) + " " + args + " 2>" + err.string());
  std::ifstream in(err);
  r.errors.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return r;
}

/// ||a − b|| / ||b||, the relative L2 distance of a simulation a from its reference b (||a − b|| when b is zero).
inline double relative_l2(const std::vector<double>& a, const std::vector<double>& b) {
  double num = 0, den = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    num += (a[k] - b[k]) * (a[k] - b[k]);
    den += b[k] * b[k];
  }
  return den > 0 ? std::sqrt(num / den) : std::sqrt(num);
}

/// Inputs the reference script tests/unit/record/signal_chain_reference.py makes as well: s ← 48271·s mod (2³¹ − 1),
/// x = s/2³¹ − 0.5 (exact in doubles, so both sides see the same x).
inline std::vector<double> lehmer(std::size_t n, std::uint64_t seed) {
  std::vector<double> x(n);
  std::uint64_t s = seed;
  for (double& value : x) {
    s = 48271 * s % 2147483647;
    value = static_cast<double>(s) / 2147483648.0 - 0.5;
  }
  return x;
}

}  // namespace dampbench::testing
