#pragma once
// `dampbench bench`: a fixed, documented workload measuring every model's batch throughput with 1 and 2
// threads, against the plain scalar loop of the same law and a vector-exp throughput probe.
#include <string>

#include "engine/cli/bench_rate.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

void add_bench_options(CLI::App* cmd, BenchOptions& options);
int bench_command(const BenchOptions& options);

}  // namespace dampbench::cli
