#include "engine/model/law_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/model/metrics.hpp"
#include "engine/model/stepped_simulation.hpp"

namespace dampbench {
namespace {

/// Candidate `index` of the batch into `c` (sized to the law model's coefficients).
void candidate_coefficients(const CandidateBatch& batch, int index, std::vector<double>& c) {
  for (std::size_t j = 0; j < c.size(); ++j) c[j] = batch.at(index, static_cast<int>(j));
}

using Family = LawFactor::Family;

/// Typical magnitude of each operating variable, to scale default bounds of higher-order coefficients.
double variable_scale(const std::string& v) {
  if (v == "I") return 3.0;      // A
  if (v == "V") return 5.0;      // V
  if (v == "phi") return 180.0;  // deg
  if (v == "amp") return 0.02;   // m
  if (v == "vamp") return 0.1;   // m/s
  return 5.0;                    // freq and w, Hz
}

/// Span of the variable over which a monotone law places its bend: sat's x0 in [0.05, 3]·span (its
/// half-point is x0·ln 2), hill's half-point h and tanh's width w in [0.05, 2]·span, tanh's steepest point
/// x1 in [0, 2]·span. The MR dampers here run 0–1 A, so I gets 1 A: x0 and the half-points then cover
/// 0.05–2 A, enough for a bend just above 0 A or a law nearly linear over the tested currents, without
/// searching bends far beyond them. variable_scale's 3 A bounds poly's slopes and stays as it is: the
/// published fixtures' bounds depend on it.
double bend_span(const std::string& v) { return v == "I" ? 1.0 : variable_scale(v); }

/// Unit of an operating variable: the unit of the positions and widths of a bend in it.
const char* variable_unit(const std::string& v) {
  if (v == "I") return "A";
  if (v == "V") return "V";
  if (v == "phi") return "deg";
  if (v == "amp") return "m";
  if (v == "vamp") return "m/s";
  return "Hz";  // freq and w
}

/// The range a factor's coefficients are bounded around: the base parameter's [lo, hi] and M = max|lo|, |hi|
/// for the first factor of a product, [0, 2] and M = 1 for every later one (those stay near 1, so that
/// the first factor carries the parameter's magnitude).
struct Level {
  double lo, hi, M;
  bool first;
};

/// Default bounds of one factor's coefficients, appended through `add(lo, hi, unit, paper_unit)`. poly: the
/// constant term keeps [lo, hi], a term of degree k gets ±2M/scale^k (the parameter may move by twice its
/// range over the variable's typical span); power and Gaussian terms are bounded around the same range.
/// sat, hill, tanh and mono have levels a in [lo, hi] and rises b, d_k ≥ 0 (at most 2M; tanh's b at most M,
/// as its bracket reaches 2): non-decreasing in the variable and never below a there by construction.
/// Units: poly, power and gauss2 coefficients carry the parameter's units, as they always have; the new
/// families' levels and rises carry them in the first factor and are pure numbers in later ones, their
/// bend positions and widths carry the variable's unit, hill's exponent is a pure number.
template <class Add>
void factor_bounds(const LawFactor& f, const Level& L, const ParameterInfo& p, Add add) {
  const double s = variable_scale(f.variable), span = bend_span(f.variable);
  auto same = [&](double lo, double hi) { add(lo, hi, p.unit, p.paper_unit); };
  auto value = [&](double lo, double hi) { L.first ? same(lo, hi) : add(lo, hi, "1", "1"); };
  auto bend = [&](double lo, double hi) { add(lo * span, hi * span, variable_unit(f.variable), variable_unit(f.variable)); };
  switch (f.family) {
    case Family::poly:
      for (int k = 0; k <= f.degree; ++k) {
        if (k == 0) same(L.lo, L.hi);
        else same(-2 * L.M / std::pow(s, k), 2 * L.M / std::pow(s, k));
      }
      break;
    case Family::power: same(-L.M, L.M); same(-2.0, 2.0); same(-L.M, L.M); break;
    case Family::gauss2:
      for (int g = 0; g < 2; ++g) {
        same(0.0, L.M);
        same(0.0, 2 * s);
        same(0.05 * s, 2 * s);
      }
      break;
    case Family::sat: value(L.lo, L.hi); value(0.0, 2 * L.M); bend(0.05, 3); break;
    case Family::hill:
      value(L.lo, L.hi);
      value(0.0, 2 * L.M);
      bend(0.05, 2);
      if (f.exponent == 0) add(1.0, 4.0, "1", "1");  // 1: saturating from the start; 4: a sharp sigmoid
      break;
    case Family::tanh: value(L.lo, L.hi); value(0.0, L.M); bend(0, 2); bend(0.05, 2); break;
    case Family::mono:
      value(L.lo, L.hi);
      for (std::size_t k = 1; k < f.knots.size(); ++k) value(0.0, 2 * L.M);
      break;
  }
}

/// Default bounds of a law's coefficients from the base parameter's bounds (factor_bounds, factor by factor).
std::vector<ParameterInfo> coefficient_infos(const ParameterInfo& p, const ParameterLaw& law) {
  const double M = std::max(std::fabs(p.lower), std::fabs(p.upper));
  const auto names = law.coefficient_names(p.name);
  std::vector<ParameterInfo> out;
  auto add = [&](double lo, double hi, const std::string& unit, const std::string& paper_unit) {
    out.push_back({names[out.size()], unit, lo, hi, paper_unit});
  };
  switch (law.kind) {
    // A law model shows its coefficients as they are (it has no to_paper_units: a base's conversion may read other
    // parameters, fvd's C that of alpha), so a free constant's paper unit is its own unit.
    case ParameterLaw::Kind::free: add(p.lower, p.upper, p.unit, p.unit); break;
    case ParameterLaw::Kind::fixed: break;
    case ParameterLaw::Kind::product:
      for (std::size_t f = 0; f < law.factors.size(); ++f)
        factor_bounds(law.factors[f], f == 0 ? Level{p.lower, p.upper, M, true} : Level{0.0, 2.0, 1.0, false}, p, add);
      break;
  }
  return out;
}

}  // namespace

LawModel::LawModel(const Model& base, std::map<std::string, ParameterLaw> laws, std::string id, std::string citation)
    : base_(base), id_(std::move(id)), citation_(std::move(citation)) {
  std::map<std::string, ParameterLaw> lag_laws;
  for (auto it = laws.begin(); it != laws.end();) {  // tau_<variable> is a driver lag unless the base has such a parameter
    const bool lag = it->first.rfind("tau_", 0) == 0 &&
                     std::none_of(base.parameters().begin(), base.parameters().end(),
                                  [&](const ParameterInfo& p) { return p.name == it->first; });
    if (lag) lag_laws.insert(*it), it = laws.erase(it);
    else (void)base.parameter_index((it++)->first);  // unknown names throw
  }
  apply_gauge(base, laws);
  std::string law_list;
  for (const auto& p : base.parameters()) {
    const auto it = laws.find(p.name);
    const ParameterLaw law = it == laws.end() ? ParameterLaw{} : it->second;
    offsets_.push_back(static_cast<int>(coefficients_.size()));
    for (auto& c : coefficient_infos(gauged_info(p), law)) coefficients_.push_back(std::move(c));
    laws_.push_back(law);
    if (it != laws.end() && !(gauge_ && p.name == gauge_->tied)) law_list += fmt::format("{}{}={}", law_list.empty() ? "" : ";", p.name, law.text());
  }
  find_law_variables();
  take_lags(lag_laws, law_list);
  if (id_.empty()) id_ = fmt::format("{}[{}]", base.id(), law_list);
  if (citation_.empty()) citation_ = std::string(base.citation());
  law_text_ = fmt::format("{} with {}", base.law(), law_list);
  if (gauge_) law_text_ += fmt::format(" (gauge {})", gauge_->meaning);
}

void LawModel::take_lags(std::map<std::string, ParameterLaw>& lag_laws, std::string& law_list) {
  const auto used = law_variables();
  for (const auto& [name, law] : lag_laws) {
    DriverLag lag;
    lag.variable = name.substr(4);
    if (std::find(used.begin(), used.end(), lag.variable) == used.end())
      throw InputError(fmt::format("{}: a driver lag of {}, which no law uses (laws in: {})", name, lag.variable,
                                   used.empty() ? "none" : fmt::format("{}", fmt::join(used, ", "))));
    if (law.kind == ParameterLaw::Kind::free) {
      lag.coefficient = static_cast<int>(coefficients_.size());
      // 0.1 ms (a current amplifier) to 0.2 s (a slow valve) for the driver's time constant.
      coefficients_.push_back({name, "s", 1e-4, 0.2, "s"});
    } else if (law.kind == ParameterLaw::Kind::fixed && law.fixed_value >= 0) {
      lag.fixed_tau_s = law.fixed_value;
    } else {
      throw InputError(fmt::format("{}: expected free or a time constant >= 0 s, got '{}'", name, law.text()));
    }
    law_list += fmt::format("{}{}={}", law_list.empty() ? "" : ";", name, law.text());
    lags_.push_back(lag);
  }
}

void LawModel::apply_gauge(const Model& base, std::map<std::string, ParameterLaw>& laws) {
  const auto own_rules = base.record_bounds_rules();
  bounds_rules_.assign(own_rules.begin(), own_rules.end());
  auto gauge = base.state_gauge();
  if (!gauge || laws.count(gauge->tied)) return;
  gauge_tied_ = base.parameter_index(gauge->tied);
  for (const auto& name : gauge->sum_of) gauge_sum_of_.push_back(base.parameter_index(name));
  laws[gauge->tied].kind = ParameterLaw::Kind::fixed;  // no coefficient; base_values writes the sum
  for (const auto& rule : gauge->bounds_rules) {
    std::erase_if(bounds_rules_, [&](const RecordBoundsRule& r) { return r.name == rule.name; });
    bounds_rules_.push_back(rule);
  }
  gauge_ = std::move(gauge);
}

ParameterInfo LawModel::gauged_info(const ParameterInfo& p) const {
  ParameterInfo out = p;
  if (gauge_)
    for (const auto& [name, unit] : gauge_->units)
      if (name == p.name) out.unit = out.paper_unit = unit;
  return out;
}

void LawModel::set_default_bounds(std::string_view name, double lower, double upper) {
  const int j = parameter_index(name);
  coefficients_[j].lower = lower;
  coefficients_[j].upper = upper;
}

void LawModel::base_values(const double* c, const std::map<std::string, double>& v, double* p) const {
  for (std::size_t j = 0; j < laws_.size(); ++j) p[j] = laws_[j].evaluate(c + offsets_[j], v);
  if (gauge_tied_ < 0) return;
  double sum = 0.0;
  for (int j : gauge_sum_of_) sum += p[j];
  p[gauge_tied_] = sum;
}

std::vector<double> LawModel::base_parameters(std::span<const double> c, const Signals& data) const {
  std::vector<double> p(laws_.size());
  base_values(c.data(), data.law_variables, p.data());
  return p;
}

std::vector<double> LawModel::base_parameters(std::span<const double> c,
                                              const std::map<std::string, double>& variables) const {
  for (const auto& v : law_variables())
    if (!variables.count(v))
      throw InputError(fmt::format("{}: no value of the operating variable '{}' its laws need", id_, v));
  std::vector<double> p(laws_.size());
  base_values(c.data(), variables, p.data());
  return p;
}

void LawModel::check_variables(const Signals& data) const {
  const auto params = base_.parameters();
  for (std::size_t j = 0; j < laws_.size(); ++j) {
    for (const auto& v : laws_[j].variables()) {
      // A column that varies over the test is followed sample by sample where the base can be stepped.
      const bool followed = data.operating_signals.count(v) && base_.stepper();
      if (const auto refused = data.operating_refused.find(v); refused != data.operating_refused.end() && !followed)
        throw InputError(fmt::format("{} (needed by the law of {})", refused->second, params[j].name));
      if (!data.law_variables.count(v))
        throw InputError(fmt::format("dataset '{}' has no operating variable '{}' (needed by the law of {}; give it "
                                     "with --set {}=... or in the dataset)",
                                     data.name, v, params[j].name, v));
    }
  }
}

void LawModel::find_law_variables() {
  law_variables_.clear();
  for (const auto& law : laws_)
    for (const auto& v : law.variables()) law_variables_.push_back(v);
  std::sort(law_variables_.begin(), law_variables_.end());
  law_variables_.erase(std::unique(law_variables_.begin(), law_variables_.end()), law_variables_.end());
}

const CandidateBatch& LawModel::base_block(const CandidateBatch& batch, int first, int count, const Signals& data) const {
  // Per-thread scratch of this law model (a law model over a law model must not share it with its base):
  // the base parameters of this block, grown once, never shrunk.
  struct Scratch {
    CandidateBatch batch;
    std::vector<double> c, p;
  };
  thread_local std::unordered_map<const LawModel*, Scratch> scratches;
  Scratch& mine = scratches[this];
  CandidateBatch& scratch = mine.batch;
  std::vector<double>& c = mine.c;
  if (scratch.dim() != base_.dim() || scratch.count() != count) scratch.resize(base_.dim(), count);
  std::vector<double>& p = mine.p;
  c.resize(coefficients_.size());
  p.resize(laws_.size());
  for (int i = 0; i < count; ++i) {
    candidate_coefficients(batch, first + i, c);
    base_values(c.data(), data.law_variables, p.data());
    for (std::size_t j = 0; j < p.size(); ++j) scratch.at(i, static_cast<int>(j)) = p[j];
  }
  return scratch;
}

bool LawModel::follows_columns(const Signals& data) const {
  if (data.operating_signals.empty()) return false;
  return std::any_of(law_variables_.begin(), law_variables_.end(),
                     [&](const std::string& v) { return data.operating_signals.count(v) > 0; });
}

std::vector<double> LawModel::stepped_force(std::span<const double> coefficients, const Signals& data) const {
  const auto nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& lag : lags_)  // a τ below 0 (a box the user gave) is a failed candidate, as a blown-up one
    if (!(lag_tau(lag, coefficients) >= 0)) return std::vector<double>(data.size(), nan);
  auto force = simulate_stepped(*this, coefficients, data, kKernelSubsteps);
  if (std::any_of(force.begin(), force.end(), [](double f) { return !std::isfinite(f); }))
    std::fill(force.begin(), force.end(), nan);  // NaN throughout, as a lane the kernels mask
  return force;
}

void LawModel::evaluate_stepped(const CandidateBatch& batch, int first, int count, const Signals& data,
                                MetricSums* out) const {
  std::vector<double> c(coefficients_.size());
  for (int i = 0; i < count; ++i) {
    candidate_coefficients(batch, first + i, c);
    const auto force = stepped_force(c, data);
    const double inf = std::numeric_limits<double>::infinity();
    out[i] = !force.empty() && std::isnan(force.front()) ? MetricSums{inf, inf, inf, inf, inf} : metric_sums(force, data);
  }
}

void LawModel::evaluate_block(const CandidateBatch& batch, int first, int count, const Signals& data,
                              SumSet wanted, MetricSums* out) const {
  if (follows_columns(data)) return evaluate_stepped(batch, first, count, data, out);
  base_.evaluate_block(base_block(batch, first, count, data), 0, count, data, wanted, out);
}

void LawModel::evaluate_block_float32(const CandidateBatch& batch, int first, int count, const Signals& data,
                                      SumSet wanted, MetricSums* out) const {
  if (follows_columns(data)) return evaluate_stepped(batch, first, count, data, out);
  base_.evaluate_block_float32(base_block(batch, first, count, data), 0, count, data, wanted, out);
}

std::vector<double> LawModel::simulate_float32(std::span<const double> coefficients, const Signals& data) const {
  if (follows_columns(data)) return simulate(coefficients, data);
  return base_.simulate_float32(base_parameters(coefficients, data), data);
}

bool LawModel::lane_costs(const CandidateBatch& batch, const Signals& data, std::span<double> out) const {
  if (follows_columns(data)) return false;  // evaluated candidate by candidate: no lane blocks to balance
  return base_.lane_costs(base_block(batch, 0, batch.count(), data), data, out);
}

void LawModel::evaluate_scalar(const CandidateBatch& batch, int first, int count, const Signals& data,
                               SumSet wanted, MetricSums* out) const {
  if (follows_columns(data)) return evaluate_stepped(batch, first, count, data, out);
  base_.evaluate_scalar(base_block(batch, first, count, data), 0, count, data, wanted, out);
}

std::vector<double> LawModel::simulate(std::span<const double> coefficients, const Signals& data) const {
  if (follows_columns(data)) return stepped_force(coefficients, data);
  return base_.simulate(base_parameters(coefficients, data), data);
}

void LawModel::simulate_block(const CandidateBatch& batch, int first, int count, const Signals& data, double* out) const {
  if (follows_columns(data)) {
    std::vector<double> c(coefficients_.size());
    for (int i = 0; i < count; ++i) {
      candidate_coefficients(batch, first + i, c);
      const auto force = stepped_force(c, data);
      std::copy(force.begin(), force.end(), out + static_cast<std::size_t>(i) * data.size());
    }
    return;
  }
  base_.simulate_block(base_block(batch, first, count, data), 0, count, data, out);
}

std::optional<std::vector<double>> LawModel::simulate_reference(std::span<const double> coefficients,
                                                                const Signals& data) const {
  if (follows_columns(data)) return std::nullopt;  // CVODE takes one set of base parameters
  return base_.simulate_reference(base_parameters(coefficients, data), data);
}

}  // namespace dampbench
