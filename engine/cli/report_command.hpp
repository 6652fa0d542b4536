#pragma once
// `dampbench report STORE [-o FILE]`: the HTML report of a sweep's store (engine/report).
#include <string>
#include <vector>

#include "engine/common/table.hpp"

namespace CLI {
class App;
}

namespace dampbench::cli {

struct ReportOptions {
  std::string store;
  std::string output;    ///< default: report.html beside the store
  int max_points = 2500;  ///< samples drawn per record
};

void add_report_options(CLI::App* cmd, ReportOptions& options);
int report_command(const ReportOptions& options);
/// Writes the HTML report of a store where `report` writes it (its computing half, the Python module's too);
/// returns the file's path and sets `bytes` (when given) to its size.
std::string write_store_report(const ReportOptions& options, std::size_t* bytes = nullptr);

}  // namespace dampbench::cli
