#pragma once
// `dampbench verify STORE`: the stored task groups of a sweep re-run and compared with the store bit for bit.
#include <string>

namespace CLI {
class App;
}

namespace dampbench::cli {

struct VerifyOptions {
  std::string store;
  int sample = 0;     ///< re-run this many stored task groups, spread evenly over the store (0: all)
  std::string spec;   ///< the sweep file (default: the path recorded in the store)
};

void add_verify_options(CLI::App* cmd, VerifyOptions& options);
int verify_command(const VerifyOptions& options);

}  // namespace dampbench::cli
