#include "engine/cli/report_command.hpp"

#include <filesystem>
#include <iostream>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "engine/cli/run_command.hpp"
#include "engine/common/error.hpp"
#include "engine/common/text_file.hpp"
#include "engine/report/store_report.hpp"

namespace dampbench::cli {

void add_report_options(CLI::App* cmd, ReportOptions& o) {
  cmd->add_option("store", o.store, "the sweep's SQLite store")->required();
  cmd->add_option("-o,--output", o.output, "HTML file (default: report.html beside the store)");
  cmd->add_option("--max-points", o.max_points, "samples drawn per record; longer records are drawn at every k-th sample (default 2500)");
}

std::string write_store_report(const ReportOptions& o, std::size_t* bytes) {
  if (o.max_points < 2) throw InputError(fmt::format("--max-points: expected an integer >= 2, got {}", o.max_points));
  const std::string output =
      o.output.empty() ? (std::filesystem::path(o.store).parent_path() / "report.html").string() : o.output;
  const sweep::Store store = sweep::Store::open(o.store);
  report::HtmlOptions options;
  options.max_points = o.max_points;
  const std::string html = report::store_report_html(store, sweep_loader(), options);
  write_text_file(output, html);
  if (bytes) *bytes = html.size();
  return output;
}

int report_command(const ReportOptions& o) {
  std::size_t bytes = 0;
  const std::string output = write_store_report(o, &bytes);
  std::cout << fmt::format("report: {} ({:.1f} MB)\n", output, static_cast<double>(bytes) / 1e6);
  return 0;
}

}  // namespace dampbench::cli
