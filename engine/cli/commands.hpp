#pragma once
// The subcommands of the `dampbench` command line. Each returns the process exit code; bad input is
// thrown as InputError and reported by main().
#include <cstdint>
#include <optional>
#include <string>

#include "engine/csv_loader.hpp"
#include "engine/dataset.hpp"

namespace dampbench::cli {

/// Where a record comes from: --input/--data file with --units and --columns.
struct DataOptions {
  std::string path;
  std::string units;    ///< "x=mm,F=kN"
  std::string columns;  ///< "t,x,v,F"
};
Dataset load_data(const DataOptions& options, bool require_force);

struct SimulateOptions {
  std::string model;
  std::string params;  ///< "name=value,..." in SI
  DataOptions input;   ///< used when sine is empty
  std::string sine;    ///< "amp=...,freq=...,cycles=...,fs=..."
  double noise_rel = 0;
  std::uint64_t seed = 1;
  std::string output;  ///< CSV path; stdout when empty
};

struct FitOptions {
  std::string model;
  DataOptions data;
  std::string metric = "of_abs";
  std::string optimizer = "pso";
  int population = 50;
  int iterations = 100;
  int runs = 50;
  std::uint64_t seed = 1;
  std::string bounds;
  std::string format = "md";
};

struct RunOptions {
  std::string preset;
  std::string output_dir;  ///< default: results/<preset name>
};

int models_command(const std::string& format);
int simulate_command(const SimulateOptions& options);
int fit_command(const FitOptions& options);
int run_command(const RunOptions& options);

}  // namespace dampbench::cli
