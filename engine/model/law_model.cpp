#include "engine/model/law_model.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench {
namespace {

/// Typical magnitude of each operating variable, to scale default bounds of higher-order coefficients.
double variable_scale(const std::string& v) {
  if (v == "I") return 3.0;      // A
  if (v == "V") return 5.0;      // V
  if (v == "phi") return 180.0;  // deg
  if (v == "amp") return 0.02;   // m
  return 5.0;                    // freq and w, Hz
}

/// Default bounds of a law's coefficients from the base parameter's bounds [lo, hi]: the leading
/// factor's constant term keeps [lo, hi], a term of degree k gets ±2M/scale^k (M = max|lo|, |hi|: the
/// parameter may move by twice its range over the variable's typical span);
/// further factors of a product are near 1; power and Gaussian terms are bounded around the same range.
std::vector<ParameterInfo> coefficient_infos(const ParameterInfo& p, const ParameterLaw& law) {
  const double M = std::max(std::fabs(p.lower), std::fabs(p.upper));
  const auto names = law.coefficient_names(p.name);
  std::vector<ParameterInfo> out;
  auto add = [&](double lo, double hi) { out.push_back({names[out.size()], p.unit, lo, hi, p.paper_unit}); };
  switch (law.kind) {
    case ParameterLaw::Kind::free: add(p.lower, p.upper); break;
    case ParameterLaw::Kind::fixed: break;
    case ParameterLaw::Kind::polynomial:
      for (std::size_t f = 0; f < law.factors.size(); ++f) {
        const auto& [var, degree] = law.factors[f];
        const double s = variable_scale(var), m = f == 0 ? 2 * M : 2.0;
        for (int k = 0; k <= degree; ++k) {
          if (k == 0) f == 0 ? add(p.lower, p.upper) : add(0.0, 2.0);
          else add(-m / std::pow(s, k), m / std::pow(s, k));
        }
      }
      break;
    case ParameterLaw::Kind::power: add(-M, M); add(-2.0, 2.0); add(-M, M); break;
    case ParameterLaw::Kind::gaussian2: {
      const double s = variable_scale(law.variable);
      for (int g = 0; g < 2; ++g) {
        add(0.0, M);
        add(0.0, 2 * s);
        add(0.05 * s, 2 * s);
      }
      break;
    }
  }
  return out;
}

}  // namespace

LawModel::LawModel(const Model& base, std::map<std::string, ParameterLaw> laws, std::string id, std::string citation)
    : base_(base), id_(std::move(id)), citation_(std::move(citation)) {
  for (const auto& [name, law] : laws) (void)base.parameter_index(name);  // unknown names throw
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
  if (id_.empty()) id_ = fmt::format("{}[{}]", base.id(), law_list);
  if (citation_.empty()) citation_ = std::string(base.citation());
  law_text_ = fmt::format("{} with {}", base.law(), law_list);
  if (gauge_) law_text_ += fmt::format(" (gauge {})", gauge_->meaning);
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

void LawModel::check_variables(const Signals& data) const {
  const auto params = base_.parameters();
  for (std::size_t j = 0; j < laws_.size(); ++j) {
    std::vector<std::string> vars;
    for (const auto& f : laws_[j].factors) vars.push_back(f.first);
    if (!laws_[j].variable.empty()) vars.push_back(laws_[j].variable);
    for (const auto& v : vars) {
      if (const auto refused = data.operating_refused.find(v); refused != data.operating_refused.end())
        throw InputError(fmt::format("{} (needed by the law of {})", refused->second, params[j].name));
      if (!data.law_variables.count(v))
        throw InputError(fmt::format("dataset '{}' has no operating variable '{}' (needed by the law of {}; give it "
                                     "with --set {}=... or in the dataset)",
                                     data.name, v, params[j].name, v));
    }
  }
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
    for (std::size_t j = 0; j < c.size(); ++j) c[j] = batch.at(first + i, static_cast<int>(j));
    base_values(c.data(), data.law_variables, p.data());
    for (std::size_t j = 0; j < p.size(); ++j) scratch.at(i, static_cast<int>(j)) = p[j];
  }
  return scratch;
}

void LawModel::evaluate_block(const CandidateBatch& batch, int first, int count, const Signals& data,
                              SumSet wanted, MetricSums* out) const {
  base_.evaluate_block(base_block(batch, first, count, data), 0, count, data, wanted, out);
}

bool LawModel::lane_costs(const CandidateBatch& batch, const Signals& data, std::span<double> out) const {
  return base_.lane_costs(base_block(batch, 0, batch.count(), data), data, out);
}

void LawModel::evaluate_scalar(const CandidateBatch& batch, int first, int count, const Signals& data,
                               SumSet wanted, MetricSums* out) const {
  base_.evaluate_scalar(base_block(batch, first, count, data), 0, count, data, wanted, out);
}

std::vector<double> LawModel::simulate(std::span<const double> coefficients, const Signals& data) const {
  return base_.simulate(base_parameters(coefficients, data), data);
}

void LawModel::simulate_block(const CandidateBatch& batch, int first, int count, const Signals& data, double* out) const {
  base_.simulate_block(base_block(batch, first, count, data), 0, count, data, out);
}

std::optional<std::vector<double>> LawModel::simulate_reference(std::span<const double> coefficients,
                                                                const Signals& data) const {
  return base_.simulate_reference(base_parameters(coefficients, data), data);
}

}  // namespace dampbench
