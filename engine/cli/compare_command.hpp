#pragma once
// `dampbench compare`: several optimizers on the same (model, datasets), side by side: best, worst, mean, std of
// the metric, success rate, evaluations to a target, convergence.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/record/record_options.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

struct CompareOptions {
  std::string model;
  std::string laws;
  std::vector<std::string> paths;
  RecordOptions data;
  std::vector<std::string> optimizers;  ///< e.g. "pso", "ga:population=80", "ga-sqp:population=240,pc=0.8"
  std::string metric = "of_abs";
  int runs = 10;
  std::uint64_t seed = 1;
  std::string bounds;
  std::string target;        ///< metric target for evaluations-to-target ("" = automatic, documented)
  long long max_evaluations = 0;  ///< budget per run for every optimizer (0 = the optimizers' own counts)
  std::string format = "md"; ///< md, csv or json
  std::string output_dir;    ///< convergence curves CSV and tables; "" = none
};

void add_compare_options(CLI::App* cmd, CompareOptions& options);
int compare_command(const CompareOptions& options);

}  // namespace dampbench::cli
