#pragma once
// `dampbench bench`: a fixed, documented workload measuring every model's batch throughput with 1 and 2
// threads, against the plain scalar loop of the same law and a vector-exp throughput probe.
#include <string>

namespace CLI {
class App;
}

namespace dampbench::cli {

struct BenchOptions {
  std::string format = "md";   ///< md or json
  std::string models;          ///< comma-separated model ids (default: all)
  double min_time_s = 0.3;     ///< each measurement repeats until it has run this long
  int trials = 3;              ///< measurements per rate; the best is reported
  std::string lanes = "float64";  ///< float64, or float32: the single-precision lanes of `--precision mixed`
  std::string workload = "sine";  ///< sine (every model, a synthetic record) or real-records (bench_real_records.hpp)
  std::string data_dir;           ///< real-records: the UTFSM records' folder (default: the shared data folder's)
};

void add_bench_options(CLI::App* cmd, BenchOptions& options);
int bench_command(const BenchOptions& options);

}  // namespace dampbench::cli
