#include "engine/fit/record_start.hpp"

#include <algorithm>
#include <stdexcept>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/fit/value_laws.hpp"
#include "engine/model/parameter_law.hpp"

namespace dampbench {
namespace {

/// p_X0 + p_X1·x + ... by least squares (the minimum-norm solution when the records cannot determine every power).
std::vector<double> polynomial_fit(const LawFactor& f, const std::vector<std::map<std::string, double>>& variables,
                                   const std::vector<double>& values) {
  const auto n = static_cast<Eigen::Index>(values.size());
  Eigen::MatrixXd basis(n, f.degree + 1);
  Eigen::VectorXd y(n);
  for (Eigen::Index r = 0; r < n; ++r) {
    const auto it = variables[r].find(f.variable);
    const double x = it == variables[r].end() ? std::nan("") : it->second;
    double power = 1;
    for (int k = 0; k <= f.degree; ++k, power *= x) basis(r, k) = power;
    y(r) = values[r];
  }
  const Eigen::VectorXd c = basis.completeOrthogonalDecomposition().solve(y);
  return {c.data(), c.data() + c.size()};
}

/// The laws fit_law_to_values fits, for its refusal: the single factors of --laws auto's families, named from
/// the candidates themselves so that the list follows them.
std::string laws_with_value_fits() {
  std::string out = "free, poly(VAR,K)";
  for (const ValueLaw& v : value_law_candidates())
    if ((v.current == ValueLaw::Shape::constant || v.factor == ValueLaw::Factor::none) && v.text() != "free")
      out += ", " + v.text();
  return out + ", and prod of a shape in I with a setting factor among them";
}

/// The family of --laws auto that `law` is, for a law that is neither fixed, free nor a single poly; InputError
/// naming the parameter when it is none of them.
ValueLaw value_law_of(const ParameterLaw& law, const std::string& parameter) {
  const std::string text = law.text();
  for (const ValueLaw& v : value_law_candidates())
    if (v.text() == text) return v;
  throw InputError(fmt::format("--start per-file: the law {}={} has no fit to per-record values (those that have one: "
                               "{})",
                               parameter, text, laws_with_value_fits()));
}

bool fitted_as_value_law(const ParameterLaw& law) {
  return law.kind == ParameterLaw::Kind::product && !law.single(LawFactor::Family::poly);
}

}  // namespace

std::vector<double> fit_law_to_values(const ParameterLaw& law, const std::string& parameter,
                                      const std::vector<std::map<std::string, double>>& variables,
                                      const std::vector<double>& values) {
  if (law.kind == ParameterLaw::Kind::fixed) return {};
  if (law.kind == ParameterLaw::Kind::free) {
    double sum = 0;
    for (double v : values) sum += v;
    return {values.empty() ? 0.0 : sum / static_cast<double>(values.size())};
  }
  if (!fitted_as_value_law(law)) return polynomial_fit(law.factors.front(), variables, values);
  return fit_value_law(value_law_of(law, parameter), variables, values).coefficients;
}

ResolvedModel per_record_model(const ModelChoice& choice) {
  ModelChoice free = choice;
  free.bounds.clear();
  free.name.clear();
  free.laws.clear();
  if (!choice.laws.empty())
    for (const auto& [name, law] : parse_laws(choice.laws, choice.option_prefix + "laws"))
      free.laws += fmt::format("{}{}={}", free.laws.empty() ? "" : ";", name,
                               law.kind == ParameterLaw::Kind::fixed ? law.text() : "free");
  return resolve_model(free);
}

std::map<std::string, ParameterLaw> laws_of(const ModelChoice& choice) {
  return choice.laws.empty() ? std::map<std::string, ParameterLaw>{}
                             : parse_laws(choice.laws, choice.option_prefix + "laws");
}

std::vector<double> laws_from_record_fits(const ModelChoice& choice, const Model& per_record, const Model& law_model,
                                          const std::vector<std::vector<double>>& fits,
                                          const std::vector<std::map<std::string, double>>& variables,
                                          std::string_view what) {
  const auto laws = laws_of(choice);
  const auto fitted = per_record.parameters();  // the base model's order, without fixed or gauge-tied parameters
  std::vector<double> start;
  std::vector<std::string> names;
  for (std::size_t j = 0; j < fitted.size(); ++j) {
    const std::string& p = fitted[j].name;
    const auto law = laws.count(p) ? laws.at(p) : ParameterLaw{};
    std::vector<double> values;
    for (const auto& f : fits) values.push_back(f[j]);
    const auto c = fit_law_to_values(law, p, variables, values);
    start.insert(start.end(), c.begin(), c.end());
    for (const auto& n : law.coefficient_names(p)) names.push_back(n);
  }
  const auto params = law_model.parameters();
  bool same = names.size() == params.size();
  for (std::size_t k = 0; same && k < names.size(); ++k) same = names[k] == params[k].name;
  if (!same) throw std::logic_error(fmt::format("{}: the start's coefficients do not match {}'s", what, law_model.id()));
  return start;
}

std::vector<double> start_from_record_fits(const LawSearch& search, const ModelChoice& choice,
                                           const Model& law_model, PreFitEffort* effort) {
  for (const auto& [name, law] : laws_of(choice))  // refused before the records' fits, which take minutes
    if (fitted_as_value_law(law)) value_law_of(law, name);
  const ResolvedModel per_record = per_record_model(choice);
  const auto fits = fit_each_record(search, per_record, effort);
  std::vector<std::map<std::string, double>> variables;
  for (const Signals* r : search.records) variables.push_back(r->law_variables);
  return laws_from_record_fits(choice, *per_record.model, law_model, fits, variables, "--start per-file");
}

void seed_from_record_fits(const PreparedFit& fit, FitRequest& request,
                           RecordFitCache* record_fits,
                           const std::function<void(const std::string&)>& progress) {
  if (!fit.start_per_file) return;
  LawSearch search = law_search(fit, request);
  search.record_fits = record_fits;
  search.progress = progress;
  search.label = "--start per-file";
  request.start = start_from_record_fits(search, fit.choice, *fit.model.model);
}

}  // namespace dampbench
