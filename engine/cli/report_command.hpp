#pragma once
// `dampbench report STORE [-o FILE]`: the HTML report of a sweep's store (engine/report).
#include <string>
#include <vector>

#include "engine/common/table.hpp"
#include "engine/fit/held_out.hpp"
#include "engine/identification/identification.hpp"
#include "engine/model/model.hpp"
#include "engine/record/signals.hpp"

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

/// What `fit --report FILE` draws: the fitted records, every run, and the fit's printed tables; with held-out
/// evaluation also each held-out record against its fold's prediction, and the held-out tables.
struct FitReport {
  const Model* model = nullptr;
  std::string optimizer, fingerprint;
  Metric metric = Metric::of_abs;
  std::vector<const Signals*> records;
  const Identification* identification = nullptr;
  bool unconfirmed = false;  ///< the automatic budget stopped before a restart confirmed the best
  std::vector<Table> tables;
  const HeldOut* held_out = nullptr;  ///< null without --predict, --folds or --reference
  std::string fold_rule;              ///< --folds (names the folds in the held-out tables)
};
/// Writes the HTML report of one fit (engine/report), whole or not at all.
void write_fit_report(const std::string& path, const FitReport& fit);

}  // namespace dampbench::cli
