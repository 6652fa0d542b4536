// simulate, evaluate, models and optimizers: the command line's simulate, evaluate and models
// (engine/cli/{simulate,evaluate,models}_command.hpp, their computing halves) on Records, and the optimizers'
// names with their settings and the fit's class defaults.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "engine/cli/evaluate_command.hpp"
#include "engine/cli/inverse_command.hpp"
#include "engine/cli/models_command.hpp"
#include "engine/cli/simulate_command.hpp"
#include "engine/common/error.hpp"
#include "engine/fit/fit_defaults.hpp"
#include "engine/model/metrics.hpp"
#include "models/registry.hpp"
#include "optimizers/registry.hpp"
#include "python/src/bindings.hpp"

namespace dampbench::python {

namespace {

py::dict simulation_dict(const cli::Simulation& sim) {
  py::dict out;
  out["t"] = to_numpy(sim.data.t_s);
  out["x"] = to_numpy(sim.data.x_m);
  out["v"] = to_numpy(sim.data.v_m_s);
  out["a"] = to_numpy(sim.data.a_m_s2);
  out["F"] = to_numpy(sim.force);
  return out;
}

/// The fit's defaults (fit_plan with nothing given) for the first registered model of each class.
py::dict fit_defaults_by_class() {
  py::dict out;
  for (const bool states : {false, true})
    for (const Model* m : all_models())
      if (m->has_internal_states() == states) {
        const FitPlan plan = fit_plan(*m, std::nullopt, std::nullopt, std::nullopt, std::nullopt);
        py::dict d;
        d["optimizer"] = plan.optimizer;
        d["population"] = plan.population;
        d["iterations"] = plan.iterations;
        d["runs"] = plan.runs;
        out[states ? "internal_states" : "algebraic"] = d;
        break;
      }
  return out;
}

void bind_simulate_function(py::module_& m) {
  m.def(
      "simulate",
      [](const std::string& model, const std::string& fixture, const std::string& laws, const std::string& params,
         const std::string& model_file, std::optional<Dataset> record, const std::string& path,
         const std::vector<std::string>& loader, const std::string& sine, double noise_rel, std::uint64_t seed,
         int fixed_step, std::optional<int> threads, std::optional<std::string> isa) {
        cli::SimulateOptions o;
        o.model = model;
        o.fixture = fixture;
        o.laws = laws;
        o.params = params;
        o.model_file = model_file;
        o.record = std::move(record);
        o.input = loader_options(path, loader);
        o.sine = sine;
        o.noise_rel = noise_rel;
        o.seed = seed;
        o.fixed_step = fixed_step;
        std::atomic<bool> stop{false};  // a simulation runs to its end: Ctrl-C is raised after it
        cli::Simulation sim;
        run_released([&] { sim = cli::run_simulate(o); }, stop, {threads, isa});
        return simulation_dict(sim);
      },
      py::arg("model"), py::arg("fixture"), py::arg("laws"), py::arg("params"), py::arg("model_file"),
      py::arg("record"), py::arg("path"), py::arg("loader"), py::arg("sine"), py::arg("noise_rel"), py::arg("seed"),
      py::arg("fixed_step"), py::arg("threads"), py::arg("isa"));
}

void bind_inverse_function(py::module_& m) {
  m.def(
      "inverse",
      [](const std::string& model, const std::string& fixture, const std::string& laws, const std::string& params,
         const std::string& model_file, std::optional<Dataset> record, const std::string& path,
         const std::vector<std::string>& loader, const std::string& range, const std::string& law, int substeps) {
        cli::InverseOptions o;
        o.damper = {model_file, model, fixture, laws, params};
        o.record = std::move(record);
        o.data = loader_options(path, loader);
        o.range = range;
        o.law = law;
        o.substeps = substeps;
        std::atomic<bool> stop{false};
        cli::InverseRun r;
        run_released([&] { r = cli::run_inverse(o); }, stop, {std::nullopt, std::nullopt});
        py::dict out;
        out["t"] = to_numpy(r.record.t_s);
        out["command"] = to_numpy(r.result.command);
        out["F_desired"] = to_numpy(r.record.F_N);
        out["F_model"] = to_numpy(r.result.force_N);
        out["reachable"] = std::vector<bool>(r.result.reachable);
        out["variable"] = r.settings.variable;
        out["share_reachable"] = r.result.share_reachable;
        out["share_at_low"] = r.result.share_at_low;
        out["share_at_high"] = r.result.share_at_high;
        out["tracking_error"] = r.result.tracking_error;
        return out;
      },
      py::arg("model"), py::arg("fixture"), py::arg("laws"), py::arg("params"), py::arg("model_file"),
      py::arg("record"), py::arg("path"), py::arg("loader"), py::arg("range"), py::arg("law"), py::arg("substeps"));
}

void bind_evaluate_function(py::module_& m) {
  m.def(
      "evaluate",
      [](const std::string& model, const std::string& laws, const std::string& params, const std::string& model_file,
         const std::vector<Dataset>& records, std::optional<std::string> isa) {
        cli::EvaluateOptions o;
        o.model = model;
        o.laws = laws;
        o.params = params;
        o.model_file = model_file;
        o.records = records;
        std::atomic<bool> stop{false};
        cli::Evaluation e;
        run_released([&] { e = cli::run_evaluate(o); }, stop, {std::nullopt, isa});
        py::list rows;
        for (const MetricRow& row : e.metrics) {
          py::dict metrics;
          for (int k = 0; k < kMetricCount; ++k) metrics[py::str(std::string(metric_name(kAllMetrics[k])))] = row[k];
          rows.append(metrics);
        }
        return rows;
      },
      py::arg("model"), py::arg("laws"), py::arg("params"), py::arg("model_file"), py::arg("records"), py::arg("isa"));
}

}  // namespace

void bind_simulate(py::module_& m) {
  bind_simulate_function(m);
  bind_inverse_function(m);
  bind_evaluate_function(m);
  m.def(
      "models",
      [](const std::vector<Dataset>& records) {
        std::vector<Signals> signals;
        signals.reserve(records.size());
        for (const Dataset& d : records) signals.push_back(prepare_signals(d));
        std::vector<const Signals*> pointers;
        for (const Signals& s : signals) pointers.push_back(&s);
        return cli::models_json(pointers).dump();
      },
      py::arg("records"));
  m.def("optimizers", [] {
    py::dict out;
    const py::dict defaults = fit_defaults_by_class();
    for (const std::string& name : optimizer_names()) {
      py::dict entry;
      entry["settings"] = optimizer_settings(name);
      py::dict default_for;
      for (const auto& [cls, plan] : defaults)
        if (py::cast<std::string>(plan["optimizer"]) == name) default_for[cls] = plan;
      entry["fit_default_for"] = default_for;
      out[py::str(name)] = entry;
    }
    return out;
  });
}

}  // namespace dampbench::python
