#pragma once
// Synthetic reference datasets of the papers' test grids, each from a documented "truth" (see
// datasets/README.md). Every record is deterministic: noise comes from keyed streams (seed, file name).
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "engine/record/dataset.hpp"

namespace dampbench::synthetic {

/// A record to write: t [s], x in `x_unit`, F in `F_unit`, with a description and operating variables.
struct Record {
  std::string file;
  std::string description;
  std::map<std::string, double> operating;  ///< SI (I A, V V, phi deg, amp m, freq Hz)
  std::vector<double> t_s, x, F;
  std::string x_unit = "mm", F_unit = "N";
};

/// Writes `# description`, `# operating: ...`, the header `t[s],x[unit],F[unit]` and the rows.
void write_record(const std::filesystem::path& dir, const Record& record);

/// Adds Gaussian noise of `relative` × RMS(F) from the stream (seed, file name).
void add_noise(std::vector<double>& F, double relative, std::uint64_t seed, const std::string& file);

/// A sinusoidal record x = amp·sin(2πft) with exact v and a, `cycles` cycles at `per_cycle` samples per
/// cycle (both ends included), and the same t and x (in mm) in `record`.
Dataset sine_record(double amp_m, double freq_hz, int cycles, int per_cycle, Record& record);

void write_fvd(const std::filesystem::path& dir, std::uint64_t seed);
void write_crfd(const std::filesystem::path& dir, std::uint64_t seed);
void write_crfd_neutral(const std::filesystem::path& dir, std::uint64_t seed);
void write_mfm(const std::filesystem::path& dir, std::uint64_t seed);
void write_mfm_neutral(const std::filesystem::path& dir, std::uint64_t seed);
void write_fdsp(const std::filesystem::path& dir, std::uint64_t seed);
void write_fdsp_neutral(const std::filesystem::path& dir, std::uint64_t seed);

}  // namespace dampbench::synthetic
