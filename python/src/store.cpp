// A sweep's store read from Python: the engine's own reader (sweep::Store::open, StoreResults) decodes every blob,
// and the module hands over columns (name → values) that python/dampbench/store.py makes into DataFrames. The
// tables and the report are the `table` and `report` commands' computing halves.
#include <atomic>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "engine/cli/report_command.hpp"
#include "engine/cli/run_command.hpp"
#include "engine/cli/table_command.hpp"
#include "engine/identification/convergence.hpp"
#include "engine/model/metrics.hpp"
#include "engine/sweep/store.hpp"
#include "engine/sweep/tables.hpp"
#include "python/src/bindings.hpp"

namespace dampbench::python {

namespace {

using sweep::GroupRecord;
using sweep::StoreHeader;

/// Runs a read of the store with the interpreter released (a store may hold 10^5 groups).
void released(const std::function<void()>& work) {
  std::atomic<bool> stop{false};  // reads have no generations to stop at: Ctrl-C is raised when they end
  run_released(work, stop, {});
}

/// The names a group is known by in tables: its part, split, fit set and datasets, model and optimizer.
struct GroupLabels {
  std::string part, split, fitset, fit, predict, model, model_id, optimizer;
  const std::vector<std::string>* params = nullptr;
};

std::string dataset_names(const StoreHeader& h, int part, const std::vector<int>& datasets) {
  std::string out;
  for (int d : datasets) out += (out.empty() ? "" : " + ") + h.datasets.at(static_cast<std::size_t>(h.dataset(part, d))).name;
  return out;
}

GroupLabels labels(const StoreHeader& h, const GroupRecord& g) {
  const auto& fitset = h.fitsets.at(static_cast<std::size_t>(h.fitset(g.part, g.split, g.fitset)));
  const auto& model = h.models.at(static_cast<std::size_t>(h.model(g.part, g.model)));
  return {h.parts.at(static_cast<std::size_t>(g.part)).name,
          h.split_name(g.part, g.split),
          fitset.label,
          dataset_names(h, g.part, fitset.fit),
          dataset_names(h, g.part, fitset.predict),
          model.name,
          model.model_id,
          h.optimizers.at(static_cast<std::size_t>(h.optimizer(g.part, g.optimizer))).label,
          &model.params};
}

/// Columns in insertion order, each a list of Python values, one per row.
class Columns {
 public:
  py::list& operator[](const std::string& name) {
    auto it = lists_.find(name);
    if (it == lists_.end()) {
      it = lists_.emplace(name, py::list()).first;
      columns_[name.c_str()] = it->second;
    }
    return it->second;
  }
  [[nodiscard]] py::dict dict() const { return columns_; }

 private:
  py::dict columns_;  // keeps the order the columns were first named in
  std::map<std::string, py::list> lists_;
};

void add_labels(Columns& c, const GroupRecord& g, const GroupLabels& l) {
  c["part"].append(l.part);
  c["group"].append(g.index);
  c["split"].append(l.split);
  c["fitset"].append(l.fitset);
  c["datasets"].append(l.fit);
  c["predict"].append(l.predict);
  c["model"].append(l.model);
  c["model_id"].append(l.model_id);
  c["laws"].append(g.laws);
  c["optimizer"].append(l.optimizer);
  c["metric"].append(std::string(metric_name(g.metric)));
}

/// The parameter names of a group's runs: its model's, or those of the law model it chose (laws = "auto"), built once
/// per (model, laws) in `chosen`.
const std::vector<std::string>* run_parameter_names(const GroupLabels& l, const GroupRecord& g,
                                                    std::map<std::string, std::vector<std::string>>& chosen) {
  if (g.laws.empty()) return l.params;
  auto [it, added] = chosen.try_emplace(l.model_id + "[" + g.laws + "]");
  if (added)
    for (const auto& p : sweep::chosen_law_model(l.model_id, g.laws).model->parameters()) it->second.push_back(p.name);
  return &it->second;
}

/// A column per parameter name (in the order the models first name them), NaN where a run's model has none.
/// A name that another column already holds is prefixed "param_".
void add_parameters(py::dict& columns, const std::vector<std::pair<const std::vector<std::string>*, const std::vector<double>*>>& rows) {
  std::vector<std::string> names;
  std::map<std::string, std::size_t> index;
  for (const auto& [params, values] : rows)
    for (const auto& n : *params)
      if (index.emplace(n, names.size()).second) names.push_back(n);
  std::vector<std::vector<double>> values(names.size(), std::vector<double>(rows.size(), std::nan("")));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto& [params, x] = rows[r];
    for (std::size_t j = 0; j < params->size() && j < x->size(); ++j) values[index.at((*params)[j])][r] = (*x)[j];
  }
  for (std::size_t j = 0; j < names.size(); ++j) {
    const std::string name = columns.contains(names[j].c_str()) ? "param_" + names[j] : names[j];
    columns[name.c_str()] = py::array_t<double>(static_cast<py::ssize_t>(rows.size()), values[j].data());
  }
}

class StoreReader {
 public:
  explicit StoreReader(const std::string& path) : store_(sweep::Store::open(path)) {}

  [[nodiscard]] std::string meta(const std::string& key) const {
    std::string value;
    released([&] {
      const std::lock_guard lock(mutex_);
      value = store_.meta(key);
    });
    return value;
  }

  py::dict runs() const {
    sweep::GroupQuery query;
    query.details = false;
    const auto [header, groups] = read_groups(query);
    Columns c;
    std::vector<std::pair<const std::vector<std::string>*, const std::vector<double>*>> params;
    std::map<std::string, std::vector<std::string>> chosen;
    for (const auto& g : groups) {
      const GroupLabels l = labels(header, g);
      const std::vector<std::string>* names = run_parameter_names(l, g, chosen);
      for (const auto& r : g.run_results) {
        add_labels(c, g, l);
        c["run"].append(r.run);
        c["best_value"].append(r.best_value);
        c["evaluations"].append(r.evaluations);
        c["stop_reason"].append(r.stop_reason);
        c["local_optimum"].append(r.at_local_optimum);
        for (std::size_t m = 0; m < kAllMetrics.size(); ++m) c[std::string(metric_name(kAllMetrics[m]))].append(r.metrics[m]);
        params.emplace_back(names, &r.params);
      }
    }
    py::dict columns = c.dict();
    add_parameters(columns, params);
    return columns;
  }

  py::dict dataset_metrics() const {
    sweep::GroupQuery query;
    query.runs = false;
    const auto [header, groups] = read_groups(query);
    Columns c;
    for (const auto& g : groups) {
      const GroupLabels l = labels(header, g);
      for (const auto& d : g.dataset_metrics) {
        add_labels(c, g, l);
        c["run"].append(d.run);
        c["dataset"].append(header.datasets.at(static_cast<std::size_t>(header.dataset(g.part, d.dataset))).name);
        c["role"].append(d.predicted ? "predict" : "fit");
        for (std::size_t m = 0; m < kAllMetrics.size(); ++m) c[std::string(metric_name(kAllMetrics[m]))].append(d.metrics[m]);
      }
    }
    return c.dict();
  }

  py::dict groups() {
    const sweep::StoreResults& R = results();
    Columns c;
    for (const auto& g : R.groups) {
      add_labels(c, g, labels(R.header, g));
      c["runs"].append(g.runs);
      c["status"].append(g.failed ? "failed" : "done");
      c["message"].append(g.message);
      c["evaluations"].append(g.evaluations);
      c["wall_time_s"].append(g.wall_time_s);
      c["candidate_samples"].append(g.candidate_samples);
      c["finished_at"].append(g.finished_at);
      const int best = g.best_run();
      c["best_run"].append(best < 0 ? py::none() : py::cast(g.run_results[static_cast<std::size_t>(best)].run));
      c["best_value"].append(best < 0 ? std::nan("") : g.run_results[static_cast<std::size_t>(best)].best_value);
      const bool ran = !g.run_results.empty();
      const Convergence conv = ran ? sweep::group_convergence(g) : Convergence{};
      c["converged"].append(ran ? py::cast(conv.converged) : py::none());
      c["verdict"].append(ran ? py::cast(conv.verdict()) : py::none());
      const auto& id = g.identifiability;
      c["identifiable"].append(id ? py::cast(id->all_identifiable()) : py::none());
      c["identifiability"].append(id ? py::cast(id->summary(R.model(g))) : py::none());
    }
    return c.dict();
  }

  std::vector<Table> tables(const cli::TableOptions& o) {
    cli::check_table_request(o);
    const sweep::StoreResults& R = results();
    std::vector<Table> out;
    released([&] { out = cli::store_tables(o, R); });
    return out;
  }

 private:
  /// The store's header and its groups as `query` asks for them, read with the interpreter released.
  std::pair<StoreHeader, std::vector<GroupRecord>> read_groups(const sweep::GroupQuery& query) const {
    std::pair<StoreHeader, std::vector<GroupRecord>> read;
    released([&] {
      const std::lock_guard lock(mutex_);
      read = {store_.header(), store_.groups(query)};
    });
    return read;
  }

  const sweep::StoreResults& results() {
    released([&] {
      const std::lock_guard lock(mutex_);
      if (!results_) results_ = std::make_unique<sweep::StoreResults>(store_, cli::sweep_loader());
    });
    return *results_;  // never replaced once read: other threads may hold it
  }
  // Taken on the worker thread only (never with the interpreter held, which would deadlock with run_released's
  // Ctrl-C checks): two Python threads may read one Store at once.
  mutable std::mutex mutex_;
  sweep::Store store_;
  std::unique_ptr<sweep::StoreResults> results_;  ///< read on the first call that needs the tables' view
};

py::list table_list(const std::vector<Table>& tables) {
  py::list out;
  for (const Table& t : tables) {
    py::list rows;
    for (const auto& row : t.rows) {
      py::list cells;
      for (const Cell& cell : row) cells.append(cell.value ? py::object(py::float_(*cell.value)) : py::object(py::str(cell.text)));
      rows.append(cells);
    }
    py::dict d;
    d["id"] = t.id;
    d["title"] = t.title;
    d["paper"] = t.paper;
    d["note"] = t.note;
    d["columns"] = t.columns;
    d["rows"] = rows;
    out.append(d);
  }
  return out;
}

}  // namespace

void bind_store(py::module_& m) {
  py::class_<StoreReader>(m, "StoreReader", "A sweep's store opened to read (the public face is dampbench.Store).")
      .def(py::init<const std::string&>(), py::arg("path"))
      .def("meta", &StoreReader::meta, py::arg("key"))
      .def("runs", &StoreReader::runs)
      .def("groups", &StoreReader::groups)
      .def("dataset_metrics", &StoreReader::dataset_metrics)
      .def(
          "tables",
          [](StoreReader& s, const std::string& kind, const std::string& split, const std::vector<std::string>& models,
             const std::vector<std::string>& optimizers, const std::string& metric, const std::string& role,
             double target_rel) {
            cli::TableOptions o;
            o.kind = kind;
            o.split = split;
            o.models = models;
            o.optimizers = optimizers;
            o.metric = metric;
            o.role = role;
            o.target_rel = target_rel;
            return table_list(s.tables(o));
          },
          py::arg("kind"), py::arg("split"), py::arg("models"), py::arg("optimizers"), py::arg("metric"),
          py::arg("role"), py::arg("target_rel"));

  m.def(
      "report",
      [](const std::string& store, const std::string& output, int max_points) {
        cli::ReportOptions o;
        o.store = store;
        o.output = output;
        o.max_points = max_points;
        std::string path;
        released([&] { path = cli::write_store_report(o); });
        return path;
      },
      py::arg("store"), py::arg("output"), py::arg("max_points"));
}

}  // namespace dampbench::python
