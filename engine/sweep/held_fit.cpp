#include "engine/sweep/held_fit.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/common/key_values.hpp"
#include "engine/model/law_model.hpp"
#include "engine/model/parameter_law.hpp"
#include "models/registry.hpp"

namespace dampbench::sweep {
namespace {

/// The fit set of group g's split fitted before g's in the ascending order of `variable`, or −1 for the first.
int fit_before(const PartPlan& part, const GroupRef& g, const std::string& variable) {
  const SplitPlan& split = part.splits[g.split];
  auto value = [&](int f) {
    const auto& vars = part.datasets[split.fitsets[f].fit.front()].signals.law_variables;
    const auto it = vars.find(variable);
    if (it == vars.end())
      throw InputError(fmt::format("hold.order: record '{}' has no variable '{}'",
                                   part.datasets[split.fitsets[f].fit.front()].signals.name, variable));
    return std::pair{it->second, f};
  };
  const auto own = value(g.fitset);
  int before = -1;
  for (int f = 0; f < static_cast<int>(split.fitsets.size()); ++f)
    if (value(f) < own && (before < 0 || value(f) > value(before))) before = f;
  return before;
}

/// ±fraction around v, as [lower, upper].
std::pair<double, double> window(double v, double fraction) {
  return {std::min(v * (1 - fraction), v * (1 + fraction)), std::max(v * (1 - fraction), v * (1 + fraction))};
}

/// The one fit set's values, or the means over several (each parameter's, and of their best values).
HeldValues mean_of(const std::vector<HeldValues>& fits) {
  if (fits.size() == 1) return fits.front();
  HeldValues out;
  for (const HeldValues& f : fits) {
    out.best_value += f.best_value;
    for (const auto& [name, v] : f.values) out.values[name] += v;
  }
  const auto n = static_cast<double>(fits.size());
  out.best_value /= n;
  for (auto& [name, v] : out.values) v /= n;
  return out;
}

}  // namespace

std::string held_laws(const ModelSpec& entry, const Model& base, const std::map<std::string, double>* values) {
  const HoldSpec& hold = *entry.hold;
  const std::map<std::string, ParameterLaw> own = parse_laws(hold.laws, entry.name);
  const auto params = base.parameters();
  for (const std::string& name : hold.free) {
    if (std::none_of(params.begin(), params.end(), [&](const ParameterInfo& p) { return p.name == name; }))
      throw InputError(fmt::format("model '{}': hold.free names '{}', which {} does not have", entry.name, name, base.id()));
    if (own.contains(name))
      throw InputError(fmt::format("model '{}': '{}' is free (hold.free) and has a law in laws: give it one or the other",
                                   entry.name, name));
  }
  std::string laws = hold.laws;
  for (const ParameterInfo& p : params) {
    if (own.contains(p.name) || std::find(hold.free.begin(), hold.free.end(), p.name) != hold.free.end()) continue;
    double v = 0.5 * (p.lower + p.upper);
    if (values) {
      const auto it = values->find(p.name);
      if (it == values->end())
        throw InputError(fmt::format("model '{}': the fit it holds to has no value of '{}'", entry.name, p.name));
      v = it->second;
    }
    laws += fmt::format("{}{}={}", laws.empty() ? "" : ";", p.name, v);  // the shortest text that reads back as v
  }
  return laws;
}

HeldValues held_values_of(const Model& model, const RunResult& best, const Signals& record) {
  if (!std::isfinite(best.best_value)) throw InputError("its fit found no finite value");
  HeldValues out{{}, best.best_value};
  const auto* law = dynamic_cast<const LawModel*>(&model);
  const std::vector<double> values = law ? law->base_parameters(best.best_params, record) : best.best_params;
  const auto params = law ? law->base().parameters() : model.parameters();
  for (std::size_t j = 0; j < params.size(); ++j) out.values.emplace(params[j].name, values[j]);
  return out;
}

ResolvedModel held_model(const Plan& plan, const GroupRef& g, const std::function<HeldValues(long long)>& fit_of,
                          std::string& laws) {
  const PartPlan& part = plan.parts()[g.part];
  const ModelSpec& entry = part.spec->models[g.model];
  const HoldSpec& hold = *entry.hold;
  const int from = part.spec->model_index(hold.from), split = part.spec->split_index(hold.split);
  const SplitPlan& source_split = part.splits[split];
  if (source_split.fitsets.size() != 1 && !hold.mean)
    throw InputError(fmt::format("model '{}' holds to '{}' in split '{}', which has {} fit sets: it needs one (or mean = "
                                 "true)",
                                 entry.name, hold.from, hold.split, source_split.fitsets.size()));
  std::vector<HeldValues> fits;  // per fit set of the source split, its lowest group
  for (int f = 0; f < static_cast<int>(source_split.fitsets.size()); ++f) {
    std::optional<HeldValues> lowest;
    for (const auto& [m, o] : source_split.pairs) {
      const long long i = m == from ? plan.group_index(g.part, split, f, m, o, g.metric) : -1;
      if (i < 0) continue;
      HeldValues v = fit_of(i);
      if (!lowest || v.best_value < lowest->best_value) lowest = std::move(v);
    }
    if (!lowest) throw InputError(fmt::format("model '{}': split '{}' fits no group of '{}'", entry.name, hold.split, hold.from));
    fits.push_back(std::move(*lowest));
  }
  const HeldValues source = mean_of(fits);
  std::optional<HeldValues> previous;
  if (hold.next > 0)
    if (const int before = fit_before(part, g, hold.order); before >= 0)
      previous = fit_of(plan.group_index(g.part, g.split, before, g.model, g.optimizer, g.metric));
  ModelChoice choice = entry;
  choice.laws = held_laws(entry, find_model(entry.model), &source.values);
  const ResolvedModel unwindowed = resolve_model(choice);
  std::string bounds;  // the entry's bounds but the free parameters', whose windows follow
  for (const auto& [name, range] : parse_key_values(entry.bounds, "bounds"))
    if (hold.mean || std::find(hold.free.begin(), hold.free.end(), name) == hold.free.end())
      bounds += fmt::format("{}{}={}", bounds.empty() ? "" : ",", name, range);
  for (const std::string& name : hold.free) {
    if (hold.mean) continue;  // their own bounds (the entry's, above, or the defaults)
    const int j = unwindowed.model->parameter_index(name);
    auto [lower, upper] = window(source.values.at(name), hold.first);
    if (previous) {
      const auto [l, u] = window(previous->values.at(name), hold.next);
      lower = std::max(lower, l), upper = std::min(upper, u);
    }
    lower = std::max(lower, unwindowed.bounds.lower[j]), upper = std::min(upper, unwindowed.bounds.upper[j]);
    if (!(lower <= upper))
      throw InputError(fmt::format("model '{}', {}: the window around the fit it holds to lies outside its bounds [{:g}, {:g}]",
                                   entry.name, name, unwindowed.bounds.lower[j], unwindowed.bounds.upper[j]));
    bounds += fmt::format("{}{}={}:{}", bounds.empty() ? "" : ",", name, lower, upper);
  }
  choice.bounds = bounds;
  laws = choice.laws;
  return resolve_model(choice);
}

std::optional<HeldValues> GroupFitCache::find(long long group) const {
  const std::lock_guard lock(mutex_);
  const auto it = fits_.find(group);
  return it == fits_.end() ? std::nullopt : std::optional<HeldValues>(it->second);
}

void GroupFitCache::store(long long group, HeldValues values) {
  const std::lock_guard lock(mutex_);
  fits_.emplace(group, std::move(values));
}

}  // namespace dampbench::sweep
