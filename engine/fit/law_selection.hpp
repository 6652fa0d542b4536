#pragma once
// `fit --laws auto`: one model of the damper whose parameters follow laws in current and in the test setting,
// the laws chosen by how well they predict records they were not fitted on.
//
//  1. What the records identify: the model, under its state gauge (engine/model/model.hpp StateGauge), fitted to
//     each training record alone (the fit's optimizer, budget and runs).
//  2. Choice: for each parameter, shared, or one of the law families of engine/fit/value_laws.hpp. A set of laws
//     is scored by folds over the training records: the laws are fitted to the fold's per-record values, predict
//     the left-out records' parameters, and the model simulates them. Leave-one-setting-out folds judge how the
//     laws follow amplitude and frequency; every fold keeps every current. When the records hold four or more
//     currents, folds that leave out each current between the lowest and the highest judge the shape in I
//     between trained currents, and the score is the mean of the two kinds' mean left-out metrics (one kind
//     alone otherwise). Coordinate search from "every parameter shared": each parameter in turn takes the family
//     with the lowest score; families within 1 % of it are a tie, broken by the Bayesian information criterion
//     of the family on the parameter's values (n·ln(RSS/n) + k·ln n). At most three passes, fewer when a pass
//     changes nothing.
//     Laws in current have up to three coefficients. With three training currents, leaving one out leaves two,
//     which cannot determine them: no current folds are made, and a family's shape between the trained currents
//     is judged only through the BIC tie-break (it decides predictions at untrained currents; the fold table
//     says which kinds of fold were made).
//  3. The chosen law model is fitted to all training records jointly, its search starting from the laws fitted
//     to the per-record values (Bounds::start).
// Cost: one fit per training record, then simulations only (candidates × folds' records per pass), then one
// joint fit.
#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "engine/common/table.hpp"
#include "engine/fit/fit.hpp"
#include "engine/fit/prepared_fit.hpp"
#include "engine/fit/record_fit_cache.hpp"
#include "engine/fit/resolve_model.hpp"
#include "engine/fit/value_laws.hpp"

namespace dampbench {

/// The most passes the choice makes over the parameters.
inline constexpr int kLawChoicePasses = 3;

/// The fewest distinct currents among the training records for which the choice also leaves currents out: with
/// four, leaving an inner one out keeps three, which determine a three-coefficient law in I.
inline constexpr std::size_t kCurrentsForShapeFolds = 4;

/// The most simulations of the training records the choice makes for a model of `parameters` parameters: every
/// family for every parameter in every pass, each record left out at most twice (by its setting's fold and its
/// current's); what the sweep's schedule counts for a laws = "auto" group.
inline double law_choice_simulations(int parameters) {
  return 2.0 * static_cast<double>(value_law_candidates().size()) * parameters * kLawChoicePasses;
}

/// How the per-record fits and the final fit are made.
struct LawSearch {
  const Model* base = nullptr;          ///< the registered model the laws act on
  std::vector<const Signals*> records;  ///< the training records
  const OptimizerFactory* optimizer = nullptr;
  std::string optimizer_name;           ///< names the fits' task keys
  IdentificationSettings settings;      ///< runs, seed, metric, budget (the task key is set per fit)
  /// Records' own fits already made, shared by the searches of one fit's folds or one sweep process; filled as
  /// records are fitted. Null: none kept.
  RecordFitCache* record_fits = nullptr;
  std::string label = "--laws auto";  ///< what the progress lines and messages say they come from
  /// Told one line per step (each record's fit, each parameter's choice, the joint fit); may be empty.
  std::function<void(const std::string&)> progress;
};

/// The search of a prepared `--laws auto` fit on `request`'s records, with its optimizer and settings; the laws act
/// on `fit`'s base model (its model itself before the laws are chosen, the chosen law model's base after).
LawSearch law_search(const PreparedFit& fit, const FitRequest& request);
/// The same for any request (a sweep group's): the laws act on `model`'s base (`model` itself when it has no laws);
/// `optimizer_name` names the per-record fits' task keys.
LawSearch law_search(const FitRequest& request, const Model& model, std::string optimizer_name);

/// The base model with its gauge and no laws: the model of the per-record fits.
ResolvedModel gauged_model(const Model& base);

/// Step 1: each training record fitted alone; the best parameters of each (the gauged model's order). Their cost
/// (made here or found in search.record_fits) is added to `effort` when given.
std::vector<std::vector<double>> fit_each_record(const LawSearch& search, const ResolvedModel& gauged,
                                                 PreFitEffort* effort = nullptr);

struct LawSelection {
  std::vector<std::string> parameters;  ///< the gauged model's parameters
  std::vector<ValueLaw> chosen;         ///< one per parameter
  std::string laws;                     ///< parse_laws text of the chosen laws (shared parameters left out)
  std::vector<double> start;            ///< the chosen law model's coefficients fitted to the per-record values
  double score = 0;                     ///< mean left-out metric of the chosen laws
  double shared_score = 0;              ///< ... and of every parameter shared
  int scored = 0;                       ///< sets of laws scored
  Table folds;                          ///< per fold: the setting or current left out, its records, both scores
  Table choices;                        ///< per parameter: the law, its coefficients, BIC, score when chosen
  /// Steps 1 and 2: the records' own fits and the choice (select_laws alone: the choice's simulated samples and
  /// wall time; fit_with_auto_laws adds the fits). A sweep group and `fit`'s output add it to the joint fit's.
  PreFitEffort effort;
};

/// The laws of the chosen law model: the chosen ones, or the first parameter `free` when every parameter is shared
/// (a law model still, so that the state gauge applies).
std::string chosen_laws_text(const LawSelection& selection);

/// Step 2 on the per-record parameters of step 1 (same order as search.records).
LawSelection select_laws(const LawSearch& search, const ResolvedModel& gauged,
                         const std::vector<std::vector<double>>& per_record);

/// Steps 1–3; `selection` receives step 2's result.
FitOutcome fit_with_auto_laws(const LawSearch& search, ResolvedModel& fitted_model, LawSelection& selection);

}  // namespace dampbench
