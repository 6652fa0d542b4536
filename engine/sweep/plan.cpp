#include "engine/sweep/plan.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "engine/common/error.hpp"
#include "engine/common/random.hpp"
#include "engine/fit/held_out.hpp"
#include "engine/sweep/fingerprint.hpp"

namespace dampbench::sweep {

LoadedDataset load_dataset(const DatasetSpec& d, const Loader& loader) {
  LoadedDataset out;
  try {
    Dataset data = loader(d.load);
    data.name = d.name;
    out.signals = prepare_signals(data);
    if (out.signals.is_system())
      throw DataError(fmt::format("dataset '{}' is a system record (t, y, u): sweeps take rig records (t, x, F); fit a "
                                  "system with `dampbench fit`",
                                  d.name));
    if (!out.signals.has_force()) throw DataError(fmt::format("dataset '{}' has no force column F", d.name));
    out.hash = dataset_hash(out.signals);
  } catch (const std::exception& e) {
    out.signals = Signals{};
    out.signals.name = d.name;
    out.error = e.what();
    out.hash = fmt::format("{:016x}", hash_key({hash_name(d.name), hash_name(out.error)}));
  }
  return out;
}

namespace {

std::string value_label(const std::vector<std::string>& vars, const std::vector<double>& values) {
  std::string s;
  for (std::size_t i = 0; i < vars.size(); ++i) s += fmt::format("{}{}={:g}", i ? "," : "", vars[i], values[i]);
  return s;
}

/// `v` without the datasets in `drop`.
std::vector<int> without(std::vector<int> v, const std::vector<int>& drop) {
  std::erase_if(v, [&](int d) { return std::find(drop.begin(), drop.end(), d) != drop.end(); });
  return v;
}

/// "a+b+c": the names of the datasets of a fit set.
std::string datasets_key(const PartSpec& part, const std::vector<int>& ds) {
  std::string k;
  for (int d : ds) {
    if (!k.empty()) k += '+';
    k += part.datasets[d].name;
  }
  return k;
}

/// Fit sets grouping the fit datasets by their values of the split's `by` variables, each predicting the
/// datasets with the same values; a dataset that failed to load forms a fit set of its own (it fails with its
/// loading message).
std::vector<FitSet> fitsets_by_variables(const PartSpec& part, const SplitSpec& split,
                                             const std::vector<LoadedDataset>& data, const std::vector<int>& fit,
                                             const std::vector<int>& predict, const std::string& where) {
  std::vector<FitSet> fitsets;
  auto name_of = [&](int d) { return part.datasets[d].name; };
  auto key_of = [&](const std::vector<int>& ds) { return datasets_key(part, ds); };
  std::map<std::vector<double>, std::vector<int>> groups;  // values → fit datasets, ordered by value
  std::vector<std::pair<std::vector<double>, std::vector<int>>> failed;
  for (int d : fit) {
    std::vector<double> values;
    for (const auto& v : split.by_variables) {
      const auto& vars = data[d].signals.law_variables;
      const auto it = vars.find(v);
      if (it == vars.end()) break;
      values.push_back(it->second);
    }
    if (values.size() != split.by_variables.size()) {
      if (data[d].ok())
        throw DataError(fmt::format("{}: dataset '{}' has no operating variable '{}' to group by", where,
                                     name_of(d), split.by_variables[values.size()]));
      failed.push_back({{}, {d}});  // fails with its loading message
      continue;
    }
    groups[values].push_back(d);
  }
  for (const auto& [values, ds] : groups) {
    std::vector<int> pred;
    for (int p : predict) {
      const auto& vars = data[p].signals.law_variables;
      bool same = true;
      for (std::size_t i = 0; i < values.size() && same; ++i) {
        const auto it = vars.find(split.by_variables[i]);
        same = it != vars.end() && it->second == values[i];
      }
      if (same) pred.push_back(p);
    }
    fitsets.push_back({ds, without(pred, ds), value_label(split.by_variables, values), key_of(ds)});
  }
  for (const auto& [values, ds] : failed) fitsets.push_back({ds, {}, name_of(ds[0]), key_of(ds)});
  return fitsets;
}

/// Fit sets of a split with `folds`: one per fold of the fit datasets (make_folds), fitted on the other folds'
/// datasets and predicting its own with the `predict` datasets that have the value it leaves out; a dataset that
/// failed to load forms a fit set of its own (it fails with its loading message).
std::vector<FitSet> fitsets_by_folds(const PartSpec& part, const SplitSpec& split, const std::vector<LoadedDataset>& data,
                                     const std::vector<int>& fit, const std::vector<int>& predict,
                                     const std::string& where) {
  std::vector<FitSet> fitsets;
  std::vector<int> loaded;
  std::vector<const Signals*> records;
  for (int d : fit) {
    if (data[d].ok()) {
      loaded.push_back(d);
      records.push_back(&data[d].signals);
    } else {
      fitsets.push_back({{d}, {}, part.datasets[d].name, part.datasets[d].name});
    }
  }
  if (records.empty()) return fitsets;  // every fit dataset failed to load: each fails with its message
  for (const Fold& fold : make_folds(records, split.folds, where + ": folds")) {
    FitSet fs;
    for (int i : fold.fit) fs.fit.push_back(loaded[i]);
    for (int i : fold.predict) fs.predict.push_back(loaded[i]);
    const Signals& left_out = *records[fold.predict.front()];
    for (int p : predict)
      if (data[p].ok() && same_fold_value(data[p].signals, left_out, split.folds) &&
          std::find(fs.predict.begin(), fs.predict.end(), p) == fs.predict.end())
        fs.predict.push_back(p);
    fs.predict = without(fs.predict, fs.fit);
    fs.label = fold.name;
    fs.key_name = datasets_key(part, fs.fit);
    fitsets.push_back(std::move(fs));
  }
  return fitsets;
}

SplitPlan plan_split(const PartSpec& part, const SplitSpec& split, const std::vector<LoadedDataset>& data) {
  SplitPlan sp;
  std::vector<int> candidates;
  for (int d = 0; d < static_cast<int>(part.datasets.size()); ++d) {
    const auto& c = split.collections;
    if (c.empty() || std::find(c.begin(), c.end(), part.datasets[d].collection) != c.end()) candidates.push_back(d);
  }
  auto selected = [&](const Selection& s) {
    std::vector<int> out;
    for (int d : candidates)
      if (s.matches(part.datasets[d].name, data[d].signals.law_variables)) out.push_back(d);
    return out;
  };
  const std::string where = split.name.empty() ? part.path : fmt::format("{}: split '{}'", part.path, split.name);
  if (candidates.empty()) return sp;  // only optional datasets, all skipped (SweepSpec::notes says so)
  const std::vector<int> fit = selected(split.fit);
  if (fit.empty())
    throw DataError(fmt::format("{}: 'fit' selects no dataset (of {} candidates)", where, candidates.size()));
  std::vector<int> predict;
  if (split.predict) {
    predict = selected(*split.predict);
    if (predict.empty()) throw DataError(fmt::format("{}: 'predict' selects no dataset", where));
  }
  auto name_of = [&](int d) { return part.datasets[d].name; };
  auto key_of = [&](const std::vector<int>& ds) { return datasets_key(part, ds); };

  switch (split.by) {
    case SplitSpec::By::each:
      for (int d : fit) sp.fitsets.push_back({{d}, without(predict, {d}), name_of(d), name_of(d)});
      break;
    case SplitSpec::By::all:
      if (!split.folds.empty()) {
        sp.fitsets = fitsets_by_folds(part, split, data, fit, predict, where);
        break;
      }
      sp.fitsets.push_back({fit, without(predict, fit),
                            fit.size() == 1 ? name_of(fit[0]) : split.name.empty() ? "all" : split.name, key_of(fit)});
      break;
    case SplitSpec::By::variables:
      sp.fitsets = fitsets_by_variables(part, split, data, fit, predict, where);
      break;
  }

  sp.pairs = part.pairs(split);
  if (sp.pairs.empty()) throw DataError(fmt::format("{}: no (model, optimizer) pair to identify", where));
  const long long metrics = static_cast<long long>(part.metrics.size());
  sp.groups = static_cast<long long>(sp.fitsets.size()) * static_cast<long long>(sp.pairs.size()) * metrics;
  long long runs = 0;
  for (const auto& [m, o] : sp.pairs) runs += part.optimizers[o].runs > 0 ? part.optimizers[o].runs : part.runs;
  sp.tasks = static_cast<long long>(sp.fitsets.size()) * runs * metrics;
  return sp;
}

}  // namespace

Plan::Plan(SweepSpec spec, const Loader& loader) : spec_(std::move(spec)) {
  for (const PartSpec& part : spec_.parts) {
    PartPlan pp;
    pp.spec = &part;
    for (const auto& m : part.models) pp.models.push_back(resolve_model_or_auto_base(m));
    for (const auto& o : part.optimizers) pp.factories.push_back(make_optimizer_factory(o.spec));
    pp.datasets.resize(part.datasets.size());
    tbb::parallel_for(std::size_t{0}, part.datasets.size(),
                      [&](std::size_t d) { pp.datasets[d] = load_dataset(part.datasets[d], loader); });
    for (const auto& s : part.splits) pp.splits.push_back(plan_split(part, s, pp.datasets));
    pp.holds_any = std::any_of(part.models.begin(), part.models.end(), [](const ModelSpec& m) { return m.hold.has_value(); });
    parts_.push_back(std::move(pp));
  }
  for (int p = 0; p < static_cast<int>(parts_.size()); ++p)
    for (int s = 0; s < static_cast<int>(parts_[p].splits.size()); ++s) {
      blocks_.push_back({groups_, p, s});
      groups_ += parts_[p].splits[s].groups;
      tasks_ += parts_[p].splits[s].tasks;
    }
}

GroupRef Plan::group(long long index) const {
  if (index < 0 || index >= groups_) throw std::out_of_range("Plan::group: no such group");
  const auto it = std::upper_bound(blocks_.begin(), blocks_.end(), index,
                                   [](long long i, const Block& b) { return i < b.first; }) - 1;
  const PartPlan& part = parts_[it->part];
  const SplitPlan& split = part.splits[it->split];
  const long long metrics = static_cast<long long>(part.spec->metrics.size());
  const long long pairs = static_cast<long long>(split.pairs.size());
  long long local = index - it->first;
  GroupRef g;
  g.index = index;
  g.part = it->part;
  g.split = it->split;
  g.metric = part.spec->metrics[local % metrics];
  local /= metrics;
  std::tie(g.model, g.optimizer) = split.pairs[local % pairs];
  g.fitset = static_cast<int>(local / pairs);
  const OptimizerEntry& opt = part.spec->optimizers[g.optimizer];
  g.runs = opt.runs > 0 ? opt.runs : part.spec->runs;
  g.task_key = hash_key({task_key(part.spec->models[g.model].name, split.fitsets[g.fitset].key_name, opt.label),
                    hash_name(metric_name(g.metric)), hash_name(part.spec->splits[g.split].name)});
  return g;
}

long long Plan::group_index(int part, int split, int fitset, int model, int optimizer, Metric metric) const {
  const auto block = std::find_if(blocks_.begin(), blocks_.end(), [&](const Block& b) { return b.part == part && b.split == split; });
  if (block == blocks_.end()) return -1;
  const PartPlan& p = parts_[part];
  const SplitPlan& s = p.splits[split];
  const auto& metrics = p.spec->metrics;
  const auto m = std::find(metrics.begin(), metrics.end(), metric);
  const auto pair = std::find(s.pairs.begin(), s.pairs.end(), std::pair{model, optimizer});
  if (m == metrics.end() || pair == s.pairs.end() || fitset < 0 || fitset >= static_cast<int>(s.fitsets.size())) return -1;
  const auto pairs = static_cast<long long>(s.pairs.size()), count = static_cast<long long>(metrics.size());
  return block->first + (fitset * pairs + (pair - s.pairs.begin())) * count + (m - metrics.begin());
}

std::string Plan::group_dataset_hash(const GroupRef& g) const {
  const PartPlan& part = parts_[g.part];
  const FitSet& fs = part.splits[g.split].fitsets[g.fitset];
  std::vector<std::string> hashes;
  for (int d : fs.fit) hashes.push_back(part.datasets[d].hash);
  for (int d : fs.predict) hashes.push_back(part.datasets[d].hash);
  return combine_hashes(hashes);
}

std::string Plan::describe(const GroupRef& g) const {
  const PartPlan& part = parts_[g.part];
  const FitSet& fs = part.splits[g.split].fitsets[g.fitset];
  return fmt::format("{}{} on {}, {}, {}", parts_.size() > 1 ? part.spec->name + ": " : "",
                     part.spec->models[g.model].name, fs.label, part.spec->optimizers[g.optimizer].label,
                     metric_name(g.metric));
}

}  // namespace dampbench::sweep
