#pragma once
// The timing loop of `dampbench bench`'s workloads (bench_command.cpp, bench_real_records.cpp).
#include <chrono>

namespace dampbench::cli {

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
