#pragma once
// `fit --start per-file`: a law model's search starts where its records, fitted one by one, put it.
//
// Each record is fitted alone by the base model with every law made a free constant (fixed values stay fixed, so
// the per-record model has the law model's gauge and fixed parameters). Each law is then fitted to its parameter's
// per-record values: a shared parameter by their mean, the families of `--laws auto` (engine/fit/value_laws.hpp)
// as `--laws auto` fits them, and a polynomial in one variable by linear least squares. Those coefficients are
// the start point (Bounds::start, member 0 of a population; the search still explores the whole box).
//
// Why: a joint fit of many coefficients over many records is where the global stages of ga-lm stall; the
// per-record fits are small problems they solve, and the laws between them are least-squares problems.
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "engine/fit/law_selection.hpp"
#include "engine/fit/prepared_fit.hpp"
#include "engine/fit/resolve_model.hpp"
#include "engine/model/parameter_law.hpp"

namespace dampbench {

/// The model of the per-record fits for the law model `choice` resolves to: its base with each law replaced by
/// a free constant (fixed laws kept).
ResolvedModel per_record_model(const ModelChoice& choice);

/// The law model's start on `search.records` (in `law_model`'s coefficient order); the per-record fits go through
/// search.record_fits, and their cost is added to `effort` when given. InputError, before any record is fitted,
/// for a law with no value fit (neither free, poly nor one of value_laws.hpp's families: gauss2, tanh, other knots
/// of mono, ...), naming the parameter and the laws that have one.
std::vector<double> start_from_record_fits(const LawSearch& search, const ModelChoice& choice,
                                           const Model& law_model, PreFitEffort* effort = nullptr);

/// `request` (of `fit`, on some of its records) with its start from its records' own fits when the fit asks for
/// one (`--start per-file`); the fits go through `record_fits` (may be null) and `progress` (may be empty).
void seed_from_record_fits(const PreparedFit& fit, FitRequest& request,
                           RecordFitCache* record_fits,
                           const std::function<void(const std::string&)>& progress);

/// The laws of `choice` by parameter (none when it has none).
std::map<std::string, ParameterLaw> laws_of(const ModelChoice& choice);

/// The law model's coefficients (in `law_model`'s order) from fits of `per_record` (per_record_model's order), one
/// per record at `variables`: each law fitted to its parameter's values. `what` names the start in the logic_error
/// of a mismatch between the two models.
std::vector<double> laws_from_record_fits(const ModelChoice& choice, const Model& per_record, const Model& law_model,
                                          const std::vector<std::vector<double>>& fits,
                                          const std::vector<std::map<std::string, double>>& variables,
                                          std::string_view what);

/// One law's coefficients fitted to values of its parameter at the records' variables (as above).
std::vector<double> fit_law_to_values(const ParameterLaw& law, const std::string& parameter,
                                      const std::vector<std::map<std::string, double>>& variables,
                                      const std::vector<double>& values);

}  // namespace dampbench
