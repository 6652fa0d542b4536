#pragma once
// Tables from a sweep's store, in Markdown, CSV, LaTeX or JSON; one file per kind in tables/, named in
// tables/registry.cpp.
//
// A series is every group of one (split, model, optimizer, optimized metric); its rows are the split's fit
// sets (conditions). Kinds:
//   runs          repeated-run statistics of the metric per condition: Mean, Max, Min, Std (fvd Tables 3–6)
//   param-stats   each parameter's mean, max, min, std over the runs per condition (fvd Tables 7–10)
//   variability   per parameter: p̄ = mean over conditions of the per-condition mean, Δp̄ = max − min, Δp̄/p̄
//                 (fvd Tables 11–14)
//   ranking       best metric per model and condition
//   fvd           runs, param-stats, variability numbered as the fvd paper's Tables 3–14, then ranking
//   params        identified parameters of the best run per condition, paper units (crfd Tables 2–3,
//                 mfm Table 2, fdsp Table 2); ‡ marks a value the record does not determine, ⊥ one at a
//                 bound; then params…_se, the relative standard errors (%) with the identifiability flags
//   errors        metric of each model's best run on each dataset, fitted and predicted (crfd Table 8,
//                 mfm Tables 4–5, fdsp Table 3)
//   energy        the energy each model's best run dissipates per cycle (∫F dx, the loop's area) on each dataset,
//                 as its difference in % from the measured one (the fvd paper's argument under its Figs. 3-4);
//                 needs the records (StoreResults' loader)
//   held-out      a model fitted on several records (laws across conditions) on each record it fitted and
//                 predicted, beside the record's own fit (the same registered model fitted to it alone) and
//                 their ratio, with the means and the worst ratio per role
//   regression    the sweep's [[regressions]]: law coefficients, R², residuals (crfd Tables 5–7, mfm eqs.
//                 5–11, fdsp eqs. 13–14); per law, on how many conditions the parameter was not
//                 identifiable (‡ on those residual rows)
//   sensitivity   SP_z per parameter and condition and their mean (crfd eqs. 4.1–4.3, Fig. 9)
//   landscape     a group's objective over a grid of two parameters (`params`, ±`range` around its best run,
//                 `points` per side) on its record, and the smallest second difference along each (fdsp Fig. 4);
//                 needs the records, as energy
//   ranksum       Mann–Whitney p-values between optimizers (same model and condition) and between models
//   bootstrap     bootstrap 95 % interval of the mean metric per condition
//   runtime       fixed-target runtime: success rate and expected running time per optimizer and problem, in
//                 evaluations and in seconds (× the group's wall seconds per evaluation), and the ECDF of
//                 runtimes over conditions and runs
//   failures      failed task groups and datasets that did not load, with their messages
//   overview      groups, tasks, failures, wall time and candidate-samples/s
//   sweep         (command line) every table the sweep file asks for
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "engine/common/table.hpp"
#include "engine/identification/convergence.hpp"
#include "engine/model/model.hpp"
#include "engine/model/parameter_law.hpp"
#include "engine/sweep/analysis.hpp"
#include "engine/sweep/spec.hpp"
#include "engine/sweep/store.hpp"
#include "engine/sweep/store_records.hpp"

namespace dampbench::sweep {

/// Whether a group's runs converged (engine/identification/convergence.hpp), from its stored runs and traces and,
/// under the automatic budget, whether it stopped before a confirming restart (its stored budget summary).
Convergence group_convergence(const GroupRecord& g);

/// The table kinds a sweep file may ask for (`sweep` is only for the command line).
std::vector<std::string> table_kinds();

/// Everything tables need, read once from a store: its header, groups (with runs and their best-so-far
/// traces, which the convergence marks and the runtime tables read), the
/// sweep file's table requests per part, and the models rebuilt for paper units.
/// The law model a group of a `laws = "auto"` model chose (GroupRecord::laws) on its registered base model: what its
/// runs' parameters are the coefficients of (the runner builds the same model from the same text).
ResolvedModel chosen_law_model(const std::string& base_model_id, const std::string& laws);

class StoreResults {
 public:
  /// `loader` reads the records again when a table needs their samples (the energy kind): once, on the first such
  /// request (reload_store_records); without one, those tables say that the records are not available.
  explicit StoreResults(const Store& store, Loader loader = {});

  const StoreHeader header;
  std::vector<GroupRecord> groups;
  std::vector<PartSpec> parts;  ///< each part's spec re-read from the stored text (tables, regressions)

  [[nodiscard]] const Model& model(int part, int model) const;
  /// The model of a group's parameters: its part's model, or the law model the group chose (GroupRecord::laws).
  [[nodiscard]] const Model& model(const GroupRecord& g) const;
  [[nodiscard]] int part_count() const { return static_cast<int>(header.parts.size()); }
  /// Every record of the header (StoreHeader::datasets' order) as read again; each says why when it was not
  /// (every one, without a loader).
  [[nodiscard]] const std::vector<StoreRecord>& records() const;
  /// Dataset `dataset` of `part` (the part's numbering) as read again, or null with the reason in `why`.
  [[nodiscard]] const Signals* record(int part, int dataset, std::string& why) const;

 private:
  Loader loader_;
  mutable std::once_flag records_read_;
  mutable std::vector<StoreRecord> records_;  ///< StoreHeader::datasets' order, read on the first record() call
  std::vector<std::vector<ResolvedModel>> models_;
  std::map<std::tuple<int, int, std::string>, ResolvedModel> chosen_;  ///< (part, model, laws) → law model
};

/// One law of a [[regressions]] entry fitted to the best run per condition (what the regression tables print
/// and the report draws).
struct LawRegression {
  std::string parameter;
  ParameterLaw law;
  RegressionFit fit;               ///< observed_i = fitted_i + residuals_i
  std::vector<bool> undetermined;  ///< per condition: the record did not determine the parameter (‡)
};
struct RegressionResult {
  const RegressionSpec* spec = nullptr;
  std::vector<std::string> conditions;                  ///< dataset names, one per per-condition fit
  std::vector<std::map<std::string, double>> variables;  ///< their operating variables
  std::vector<LawRegression> laws;
  std::string error;  ///< why the laws could not be fitted ("" when they were)
};
/// Every [[regressions]] entry of a part, fitted on the lowest-metric single-dataset fit per condition.
std::vector<RegressionResult> law_regressions(const StoreResults& results, int part);

/// The tables of one kind for one part, filtered by `request` (kind, split, models, optimizers, metric,
/// role, where, target_rel; paper and title label them).
std::vector<Table> make_tables(const StoreResults& results, int part, const TableSpec& request);

/// Every table a part's sweep file asks for (its `tables`), regression and failures included when present.
std::vector<Table> sweep_tables(const StoreResults& results, int part);

/// Every table in one format ("md", "csv", "latex", "json"); InputError for another format. JSON is
/// {"tables": [{id, title, paper, note, columns, rows}]} with the numbers of the cells as numbers.
std::string format_tables(const std::vector<Table>& tables, const std::string& format);
std::string tables_to_json(const std::vector<Table>& tables);

}  // namespace dampbench::sweep
