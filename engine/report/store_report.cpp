#include "engine/report/store_report.hpp"

#include <algorithm>
#include <functional>

#include <fmt/format.h>

#include "engine/common/error.hpp"
#include "engine/fit/auto_budget.hpp"
#include "engine/sweep/spec.hpp"
#include "engine/sweep/tables.hpp"

namespace dampbench::report {
namespace {

/// Everything a store's report points into, alive while the report is rendered.
class StoreSources {
 public:
  StoreSources(const sweep::Store& store, const sweep::Loader& loader) : results_(store, loader) {
    const sweep::StoreHeader& h = results_.header;
    if (results_.groups.empty())
      throw StoreError(fmt::format("{}: the store holds no finished task group, so there is nothing to report (run the "
                                   "sweep into it first: dampbench run SWEEP --store {})",
                                   store.path(), store.path()));
    load_records();
    const bool many_parts = results_.part_count() > 1;
    auto prefix = [&](int p) { return many_parts ? h.parts[static_cast<std::size_t>(p)].name + ": " : std::string(); };

    input_.title = fmt::format("dampbench report — {}", h.name);
    input_.fingerprint = {{"sweep", h.name},
                          {"store", store.path()},
                          {"dampbench", h.dampbench_version},
                          {"build", h.build_flags},
                          {"spec hash", h.spec_hash},
                          {"spec file", h.spec_path},
                          {"task groups stored", fmt::format("{} of {}", results_.groups.size(), h.groups)}};
    for (const auto& d : h.datasets)
      input_.fingerprint.emplace_back(fmt::format("data {}{}", prefix(d.part), d.name), d.hash);
    if (results_.groups.size() < static_cast<std::size_t>(h.groups))
      input_.notes.push_back(fmt::format("The sweep is not finished: {} of {} task groups are stored; a resumed run adds "
                                         "the rest.",
                                         results_.groups.size(), h.groups));
    const auto failed = std::count_if(results_.groups.begin(), results_.groups.end(), [](const auto& g) { return g.failed; });
    if (failed > 0) input_.notes.push_back(fmt::format("{} task groups failed (see the failures table).", failed));

    for (const sweep::GroupRecord& g : results_.groups) {
      if (g.failed || g.run_results.empty()) continue;
      const auto& fs = h.fitsets.at(static_cast<std::size_t>(h.fitset(g.part, g.split, g.fitset)));
      FitInput f;
      f.part = h.parts[static_cast<std::size_t>(g.part)].name;
      f.split = h.split_name(g.part, g.split);
      f.condition = fs.label;
      f.model_name = h.models.at(static_cast<std::size_t>(h.model(g.part, g.model))).name;
      f.optimizer = h.optimizers.at(static_cast<std::size_t>(h.optimizer(g.part, g.optimizer))).label;
      f.model = &results_.model(g);
      f.metric = g.metric;
      for (int d : fs.fit) f.fit.push_back(h.dataset(g.part, d));
      for (int d : fs.predict) f.predict.push_back(h.dataset(g.part, d));
      f.runs = g.run_results;
      f.unconfirmed = stopped_before_converging(g.message);
      input_.fits.push_back(std::move(f));
    }
    for (int p = 0; p < results_.part_count(); ++p) {
      for (sweep::RegressionResult& r : sweep::law_regressions(results_, p))
        for (sweep::LawRegression& law : r.laws)
          input_.laws.push_back({fmt::format("{}{} ({}) — {}", prefix(p), r.spec->name, r.spec->model, law.parameter),
                                 r.conditions, r.variables, std::move(law)});
      add_runtimes(p, prefix(p));
      for (Table& r : sweep::sweep_tables(results_, p)) {
        r.title = prefix(p) + r.title;
        input_.tables.push_back(std::move(r));
      }
    }
  }

  [[nodiscard]] const ReportInput& input() const { return input_; }

 private:
  /// The fixed-target runtime (ERT) tables and their ECDFs where a split compares optimizers: those of the part's
  /// own `runtime` tables (their targets and filters), else of one runtime request with the defaults.
  void add_runtimes(int part, const std::string& prefix) {
    std::vector<sweep::TableSpec> requests;
    for (const sweep::TableSpec& t : results_.parts.at(static_cast<std::size_t>(part)).tables)
      if (t.kind == "runtime") requests.push_back(t);
    if (requests.empty()) requests.emplace_back().kind = "runtime";
    for (const sweep::TableSpec& request : requests) {
      // The kind gives its tables in pairs: the ERT table of a (split, metric), then its ECDF.
      std::vector<Table> made = sweep::make_tables(results_, part, request);
      for (std::size_t i = 0; i + 1 < made.size(); i += 2) {
        Table& ert = made[i];
        Table& ecdf = made[i + 1];
        if (ecdf.columns.size() <= 2) continue;  // one optimizer: nothing is compared
        ert.title = prefix + ert.title;
        ecdf.title = prefix + ecdf.title;
        input_.runtimes.push_back(std::move(ert));
        input_.ecdfs.push_back(std::move(ecdf));
      }
    }
  }

  /// Every dataset the store names, read again from the (re-parsed) sweep file of its part.
  void load_records() {
    const std::vector<sweep::StoreRecord>& loaded = results_.records();
    input_.records.resize(loaded.size());
    for (std::size_t i = 0; i < loaded.size(); ++i) {
      RecordInput& r = input_.records[i];
      r.name = results_.header.datasets[i].name;
      r.label = results_.header.datasets[i].label;
      r.signals = loaded[i].signals();
      r.unavailable = loaded[i].unavailable;
      if (!r.signals) input_.notes.push_back(fmt::format("Record '{}' is not drawn: {}.", r.name, r.unavailable));
    }
  }

  sweep::StoreResults results_;
  ReportInput input_;
};

}  // namespace

nlohmann::ordered_json store_report_data(const sweep::Store& store, const sweep::Loader& loader, const HtmlOptions& options) {
  const StoreSources sources(store, loader);
  return report_data(sources.input(), options);
}

std::string store_report_html(const sweep::Store& store, const sweep::Loader& loader, const HtmlOptions& options) {
  const StoreSources sources(store, loader);
  return render_html(sources.input(), options);
}

}  // namespace dampbench::report
