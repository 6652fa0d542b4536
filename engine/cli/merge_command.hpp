#pragma once
// `dampbench merge OUT PART...`: the stores of a sweep's shards (run --shard i/n) joined into one
// (engine/distributed/merge.hpp).
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace dampbench::cli {

struct MergeOptions {
  std::string out;
  std::vector<std::string> parts;
};

void add_merge_options(CLI::App* cmd, MergeOptions& options);
int merge_command(const MergeOptions& options);

}  // namespace dampbench::cli
