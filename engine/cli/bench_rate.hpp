#pragma once
// The options and the timing loop of `dampbench bench`'s workloads (bench_command.cpp, bench_real_records.cpp).
#include <chrono>
#include <string>

namespace dampbench::cli {

/// What `dampbench bench` measures and how (its command-line options).
struct BenchOptions {
  std::string format = "md";   ///< md or json
  std::string models;          ///< comma-separated model ids (default: all)
  double min_time_s = 0.3;     ///< each measurement repeats until it has run this long
  int trials = 3;              ///< measurements per rate; the best is reported
  std::string lanes = "float64";  ///< float64, or float32: the single-precision lanes of `--precision mixed`
  std::string workload = "sine";  ///< sine (every model, a synthetic record) or real-records (bench_real_records.hpp)
  std::string data_dir;           ///< real-records: the UTFSM records' folder (default: the shared data folder's)
};

/// Repeats `work` (which processes `items` items) until min_time_s has passed, after one warm-up call; items per
/// second.
template <class Work>
double rate(double items, double min_time_s, Work&& work) {
  work();  // warm-up
  const auto start = std::chrono::steady_clock::now();
  long long reps = 0;
  double elapsed = 0;
  do {
    work();
    ++reps;
    elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } while (elapsed < min_time_s);
  return items * static_cast<double>(reps) / elapsed;
}

}  // namespace dampbench::cli
