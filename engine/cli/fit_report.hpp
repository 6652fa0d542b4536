#pragma once
// `fit --report FILE`: the HTML report of one fit (engine/report), drawn from what the fit command has in hand.
#include <string>
#include <vector>

#include "engine/common/table.hpp"
#include "engine/fit/held_out.hpp"
#include "engine/identification/identification.hpp"
#include "engine/model/model.hpp"
#include "engine/record/signals.hpp"

namespace dampbench::cli {

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
