// A store read once for its tables: header, groups with their traces, the parts' specs, the rebuilt models.
#include "engine/sweep/tables.hpp"

#include <utility>

namespace dampbench::sweep {

StoreResults::StoreResults(const Store& store, Loader loader) : header(store.header()), loader_(std::move(loader)) {
  GroupQuery q;
  q.traces = true;
  groups = store.groups(q);
  for (const auto& p : header.parts) {
    SpecOptions o;
    o.check_files = false;
    parts.push_back(std::move(parse_sweep(p.source, p.path, o).parts.at(0)));
  }
  models_.resize(header.parts.size());
  for (const auto& m : header.models) {
    ModelSpec s;
    s.name = m.name;
    s.model = m.model_id;
    s.fixture = m.fixture;
    s.laws = m.laws;
    models_[static_cast<std::size_t>(m.part)].push_back(resolve_model_or_auto_base(s));
  }
  for (const GroupRecord& g : groups) {
    if (g.laws.empty() || chosen_.contains({g.part, g.model, g.laws})) continue;
    const std::string& base = header.models.at(static_cast<std::size_t>(header.model(g.part, g.model))).model_id;
    chosen_.emplace(std::tuple{g.part, g.model, g.laws}, chosen_law_model(base, g.laws));
  }
}

ResolvedModel chosen_law_model(const std::string& base_model_id, const std::string& laws) {
  ModelChoice choice;
  choice.model = base_model_id;
  choice.laws = laws;
  return resolve_model(choice);
}

const Model& StoreResults::model(const GroupRecord& g) const {
  return g.laws.empty() ? model(g.part, g.model) : *chosen_.at({g.part, g.model, g.laws}).model;
}

const Model& StoreResults::model(int part, int m) const {
  return *models_.at(static_cast<std::size_t>(part)).at(static_cast<std::size_t>(m)).model;
}

const std::vector<StoreRecord>& StoreResults::records() const {
  std::call_once(records_read_, [&] {
    if (loader_) {
      records_ = reload_store_records(header, loader_);
      return;
    }
    records_.resize(header.datasets.size());
    for (StoreRecord& r : records_)
      r.unavailable = "the records were not read again with the store (tables of the energy kind need their samples)";
  });
  return records_;
}

const Signals* StoreResults::record(int part, int dataset, std::string& why) const {
  const StoreRecord& r = records().at(static_cast<std::size_t>(header.dataset(part, dataset)));
  why = r.unavailable;
  return r.signals();
}

}  // namespace dampbench::sweep
