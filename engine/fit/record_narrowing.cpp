#include "engine/fit/record_narrowing.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/fit/record_start.hpp"
#include "engine/model/bounds.hpp"
#include "engine/model/parameter_law.hpp"

namespace dampbench {
namespace {

/// The single poly factor of `law`, or null for a shared parameter (free, poly of degree 0).
const LawFactor* slope_factor(const ParameterLaw& law, const std::string& parameter) {
  if (law.kind == ParameterLaw::Kind::free || law.kind == ParameterLaw::Kind::fixed) return nullptr;
  if (law.single(LawFactor::Family::poly) && law.factors.front().degree <= 1)
    return law.factors.front().degree == 0 ? nullptr : &law.factors.front();
  throw InputError(fmt::format("narrow: the law {}={} has no box from a narrowed range (those that have one: free, "
                               "poly(VAR,0), poly(VAR,1))",
                               parameter, law.text()));
}

/// [v0, v1] of `variable` over the records; InputError when it takes one value (a slope over it has no bound).
std::pair<double, double> variable_span(const std::vector<const Signals*>& records, const std::string& variable,
                                        const std::string& parameter) {
  double v0 = INFINITY, v1 = -INFINITY;
  for (const Signals* r : records) {
    const auto it = r->law_variables.find(variable);
    if (it == r->law_variables.end())
      throw InputError(fmt::format("narrow: record '{}' has no operating variable '{}' ({}'s law)", r->name, variable, parameter));
    v0 = std::min(v0, it->second), v1 = std::max(v1, it->second);
  }
  if (!(v1 > v0))
    throw InputError(fmt::format("narrow: {}'s law is linear in {}, which is {} on every record: the records "
                                 "bound no slope",
                                 parameter, variable, v0));
  return {v0, v1};
}

/// Appends the coefficients' ranges of one parameter's law from its range [lo, hi] (the header's rules).
void append_law_box(const ParameterLaw& law, const std::string& parameter, double lo, double hi,
                    const std::vector<const Signals*>& records, Bounds& box) {
  const LawFactor* f = slope_factor(law, parameter);
  if (!f) {
    box.lower.push_back(lo), box.upper.push_back(hi);
    return;
  }
  const auto [v0, v1] = variable_span(records, f->variable, parameter);
  const double slope = (hi - lo) / (v1 - v0);
  const double vr = std::min(std::abs(v0), std::abs(v1)) == std::abs(v0) ? v0 : v1;
  box.lower.push_back(lo - slope * std::abs(vr)), box.upper.push_back(hi + slope * std::abs(vr));
  box.lower.push_back(-slope), box.upper.push_back(slope);
}

std::string summary_of(const NarrowingResult& n, const Model& per_record, std::size_t records) {
  std::string failed;
  for (const NarrowingRound& r : n.rounds) failed += fmt::format("{}{}", failed.empty() ? "" : ", ", r.failed_conditions);
  double widest = 0;
  std::string widest_name;
  const auto params = per_record.parameters();
  const NarrowingRound& first = n.rounds.front();
  for (int j = 0; j < per_record.dim(); ++j) {
    const double start_width = first.bounds.upper[j] - first.bounds.lower[j];
    const double share = start_width > 0 ? (n.final_bounds.upper[j] - n.final_bounds.lower[j]) / start_width : 0;
    if (share >= widest) widest = share, widest_name = params[j].name;
  }
  double best_lo = INFINITY, best_hi = -INFINITY;  // the last round's per-record fits
  for (const NarrowingCondition& c : n.rounds.back().conditions)
    if (!c.failed) best_lo = std::min(best_lo, c.best_value), best_hi = std::max(best_hi, c.best_value);
  return fmt::format("bounds narrowed over {} records in {} rounds (failed records per round: {}; the last round's "
                     "fits {:.4g} to {:.4g}; the widest final range, {}, is {:.3g} % of its first){}",
                     records, n.rounds.size(), failed, best_lo, best_hi, widest_name, 100 * widest,
                     n.completed() ? "" : "; stopped: " + n.stop_reason);
}

}  // namespace

void check_narrowable_laws(const ModelChoice& choice) {
  for (const auto& [name, law] : laws_of(choice)) slope_factor(law, name);
}

NarrowedStart narrowed_start(const ModelChoice& choice, const Model& law_model, const std::vector<const Signals*>& records,
                             const OptimizerSpec& inner, const IdentificationSettings& settings, const NarrowingSpec& spec) {
  check_narrowable_laws(choice);
  if (spec.from != "default" && spec.from != "wide")
    throw InputError(fmt::format("narrow: from: expected \"default\" or \"wide\", got '{}'", spec.from));
  const auto laws = laws_of(choice);
  const ResolvedModel per_record = per_record_model(choice);
  const Model& base = *per_record.model;
  const Bounds start = spec.from == "wide" ? wide_bounds(base) : per_record.bounds_for(records, RecordBox::hull);
  NarrowedStart out;
  out.narrowing = narrow_bounds(base, records, start, inner, spec.rounds, settings);
  for (const NarrowingRound& r : out.narrowing.rounds) {
    out.effort.wall_time_s += r.wall_time_s;
    for (std::size_t c = 0; c < r.conditions.size(); ++c) {
      out.effort.evaluations += r.conditions[c].evaluations;
      out.effort.candidate_samples +=
          static_cast<double>(r.conditions[c].evaluations) * static_cast<double>(records[c]->size());
    }
  }
  const auto fitted = base.parameters();
  for (int j = 0; j < base.dim(); ++j) {
    const std::string& p = fitted[j].name;
    append_law_box(laws.count(p) ? laws.at(p) : ParameterLaw{}, p, out.narrowing.final_bounds.lower[j],
                   out.narrowing.final_bounds.upper[j], records, out.box);
  }
  if (out.box.dim() != law_model.dim())
    throw std::logic_error(fmt::format("narrow: the box's coefficients do not match {}'s", law_model.id()));
  std::vector<std::vector<double>> fits;  // the last round's records that did not fail
  std::vector<std::map<std::string, double>> variables;
  for (std::size_t c = 0; c < out.narrowing.rounds.back().conditions.size(); ++c)
    if (const NarrowingCondition& cond = out.narrowing.rounds.back().conditions[c]; !cond.failed)
      fits.push_back(cond.best_params), variables.push_back(records[c]->law_variables);
  if (!fits.empty()) out.start = laws_from_record_fits(choice, base, law_model, fits, variables, "narrow");
  if (!out.start.empty()) clamp_into_box(law_model, out.box, out.start);
  out.summary = summary_of(out.narrowing, base, records.size());
  return out;
}

}  // namespace dampbench
