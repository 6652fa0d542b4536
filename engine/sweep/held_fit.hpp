#pragma once
// Models fitted from another model's fit (a [[models]] entry's `hold`, HoldSpec in spec.hpp): the fdsp paper's second
// identification step (§5.2), where a_c0 and a_c1 are re-identified at each frequency with every other parameter held
// at the 2.5 Hz fit, within ±40 % of that fit's values at the first frequency and ±20 % of the previous frequency's
// after it. The fits a group holds to are the sweep's own groups (the runner makes them where they are needed,
// engine/sweep/runner.cpp), never numbers written into the sweep file.
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "engine/fit/resolve_model.hpp"
#include "engine/identification/identification.hpp"
#include "engine/model/model.hpp"
#include "engine/sweep/plan.hpp"
#include "engine/sweep/spec.hpp"

namespace dampbench::sweep {

/// The laws of a held model: the entry's own laws (HoldSpec::laws), then every parameter of the registered model `base` that is
/// neither free nor given a law there, fixed at its value in `values` (by name), or at the middle of its default
/// bounds without `values` (the placeholder the plan's model carries before a group knows the fit it holds to).
/// InputError naming the entry for a free parameter the base model lacks or one the entry's laws also set.
std::string held_laws(const ModelSpec& entry, const Model& base, const std::map<std::string, double>* values = nullptr);

/// A group's best run as another group holds to it: its base model's parameter values by name, and its best metric.
struct HeldValues {
  std::map<std::string, double> values;
  double best_value = 0;
};

/// `best` (a run of `model`) as a held group reads it: the base model's parameters (a law model's at `record`'s
/// variables) and the run's metric. InputError when the run found no finite value.
HeldValues held_values_of(const Model& model, const RunResult& best, const Signals& record);

/// The model a held group fits (HoldSpec): every parameter but the free ones at the lowest best run of the source
/// model's groups in the source split, the free ones within ±first of it and, with `next`, ±next of the fit before
/// this one in `order` (itself fitted that way). `fit_of(group)` gives a group's HeldValues (the runner's cache, or
/// a fit made there); `laws` receives the held laws (GroupRecord::laws). InputError when the source split has
/// several fit sets or a window lies outside the entry's bounds.
ResolvedModel held_model(const Plan& plan, const GroupRef& g, const std::function<HeldValues(long long)>& fit_of,
                         std::string& laws);

/// HeldValues by group number, made once per process and shared by the groups that hold to them. A group's fit
/// depends only on its number and the plan, so one found here has the bits the group would make; two groups that
/// need the same fit at once may both make it (the first stays), as RecordFitCache's fits.
class GroupFitCache {
 public:
  [[nodiscard]] std::optional<HeldValues> find(long long group) const;
  void store(long long group, HeldValues values);

 private:
  mutable std::mutex mutex_;
  std::map<long long, HeldValues> fits_;
};

}  // namespace dampbench::sweep
