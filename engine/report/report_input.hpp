#pragma once
// What an HTML report shows (html_report.hpp), gathered from a sweep's store (store_report.hpp) or from one
// `dampbench fit` (engine/cli): the records, the repeated runs of every model fitted to every condition, the
// regressions of identified parameters on operating variables, and the store's tables. Pointers refer to
// objects the caller keeps alive while the report is rendered.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/model/metrics.hpp"
#include "engine/model/model.hpp"
#include "engine/record/signals.hpp"
#include "engine/sweep/store.hpp"
#include "engine/sweep/tables.hpp"

namespace dampbench::report {

/// A record the loops are drawn from; `signals` is null when it could not be read again (`unavailable` says why).
struct RecordInput {
  std::string name, label;
  const Signals* signals = nullptr;
  std::string unavailable;
};

/// The repeated runs of one model fitted by one optimizer to one condition (a sweep's task group).
struct FitInput {
  std::string part, split, condition;  ///< condition: the fit set's label
  std::string model_name, optimizer;   ///< the sweep's labels
  const Model* model = nullptr;
  Metric metric = Metric::of_abs;
  std::vector<int> fit, predict;  ///< indices into ReportInput::records
  std::vector<sweep::RunRecord> runs;  ///< with their best-so-far traces
  bool unconfirmed = false;  ///< the automatic budget stopped before a restart confirmed the best (not converged)
};

/// One law of a regression, drawn over the identified points.
struct LawFigureInput {
  std::string title;  ///< "part: regression name — model"
  std::vector<std::string> conditions;
  std::vector<std::map<std::string, double>> variables;
  sweep::LawRegression law;
};

/// A record predicted by a fit it was held out of (held-out evaluation): drawn measured against the prediction.
struct PredictionInput {
  int record = 0;                  ///< index into ReportInput::records
  std::string fold, fitted_on;     ///< the fold whose fit predicts it ("all": the fit on every fitted record)
  std::string model_name, optimizer;
  Metric metric = Metric::of_abs;
  double value = 0;                ///< the record's metric under the prediction
  std::optional<double> per_file;  ///< the metric of the record's own per-file fit, when known
  std::vector<double> params;      ///< the fold's best parameters
  const std::vector<double>* force = nullptr;  ///< the predicted force at every sample (Model::simulate of params)
};

struct ReportInput {
  std::string title;
  std::vector<std::pair<std::string, std::string>> fingerprint;  ///< (what, value): version, build, hashes
  std::vector<std::string> notes;                                ///< shown under the title
  std::vector<RecordInput> records;
  std::vector<FitInput> fits;
  std::vector<LawFigureInput> laws;
  std::vector<PredictionInput> predictions;  ///< held-out records, grouped by fold in the order of their first record
  std::vector<Table> ecdfs;   ///< fixed-target runtime ECDF tables (column 0: evaluations, then one per optimizer)
  std::vector<Table> runtimes;  ///< the fixed-target runtime tables (success, ERT, ERT s) those ECDFs come from
  std::vector<Table> tables;  ///< the sweep's tables, as `dampbench table --kind sweep` prints them
};

}  // namespace dampbench::report
