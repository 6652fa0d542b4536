// libFuzzer target: a sweep file (engine/sweep/spec.hpp) parsed and checked, files not opened, and the same text as
// the paper file of a reproduction (engine/sweep/reproduction.hpp) against a small table of ours. Bad input must
// end in an InputError naming file, line and key; anything else is a bug.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/common/error.hpp"
#include "engine/sweep/reproduction.hpp"
#include "engine/sweep/spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  dampbench::sweep::SpecOptions options;
  options.check_files = false;
  try {
    (void)dampbench::sweep::parse_sweep(text, "/nonexistent/fuzz/sweep.toml", options);
  } catch (const dampbench::InputError&) {
  }
  static const std::vector<dampbench::Table> ours = [] {
    dampbench::Table t{"table03_of_abs_fvd.linear_viscous", "", {"Test", "Mean", "Min"}, {}};
    t.rows.push_back({"Test 1", dampbench::number_cell(0.2), dampbench::number_cell(0.1)});
    t.rows.push_back({"Test 2", "n/a", dampbench::number_cell(0.0)});
    return std::vector<dampbench::Table>{t};
  }();
  try {
    const auto r = dampbench::sweep::reproduce_text({"/nonexistent/fuzz/paper.toml", "synthetic", "x", true, ""}, text, ours);
    (void)dampbench::sweep::reproduction_markdown(r);
    (void)dampbench::sweep::reproduction_json(r, {"Test 1"});
  } catch (const dampbench::InputError&) {
  }
  return 0;
}
