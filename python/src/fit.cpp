// fit: the command line's fit (engine/cli/fit_run.hpp, run_fit_options and fit_json) on Records, with the
// interpreter released while it runs; the result is the JSON that `dampbench fit --format json` prints.
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "engine/cli/fit_run.hpp"
#include "python/src/bindings.hpp"

namespace dampbench::python {

void bind_fit(py::module_& m) {
  m.def(
      "fit",
      [](const std::string& model, const std::vector<Dataset>& records, const std::string& laws,
         const std::string& bounds, const std::string& metric, std::optional<std::string> optimizer,
         const std::string& optimizer_settings, std::optional<int> pop, std::optional<int> iters,
         std::optional<int> runs, const std::string& budget, std::optional<long long> max_evals,
         std::optional<double> max_seconds, std::uint64_t seed, const std::string& start, const std::string& precision,
         const std::vector<std::string>& predict, const std::vector<std::string>& loader, const std::string& folds, const std::string& reference, const std::string& report,
         const std::string& save_model, std::optional<int> threads, std::optional<std::string> isa) {
        std::atomic<bool> stop{false};
        cli::FitOptions o;
        FitSpec& spec = o.fit;
        spec.model.option_prefix = "--";
        spec.model.model = model;
        spec.model.laws = laws;
        spec.model.bounds = bounds;
        spec.records = records;
        spec.metric = metric;
        spec.optimizer = optimizer;
        spec.optimizer_settings = optimizer_settings;
        spec.population = pop;
        spec.iterations = iters;
        spec.runs = runs;
        spec.budget = budget;
        spec.max_evaluations = max_evals;
        spec.max_seconds = max_seconds;
        spec.seed = seed;
        spec.start = start;
        spec.precision = precision;
        spec.stop = &stop;
        // Loader options for the --predict files, as the records' were read (units, columns, transform,
        // average_cycles, conditions, set).
        spec.data = loader_options("", loader);
        o.held_out.predict = predict;
        o.held_out.folds = folds;
        o.held_out.reference = reference;
        o.report = report;
        o.save_model = save_model;
        std::string json;
        run_released([&] { json = cli::fit_json(o, cli::run_fit_options(o)).dump(); }, stop, {threads, isa});
        return json;
      },
      py::arg("model"), py::arg("records"), py::arg("laws"), py::arg("bounds"), py::arg("metric"), py::arg("optimizer"),
      py::arg("optimizer_settings"), py::arg("pop"), py::arg("iters"), py::arg("runs"), py::arg("budget"),
      py::arg("max_evals"), py::arg("max_seconds"), py::arg("seed"), py::arg("start"), py::arg("precision"),
      py::arg("predict"),
      py::arg("loader"), py::arg("folds"), py::arg("reference"), py::arg("report"), py::arg("save_model"),
      py::arg("threads"), py::arg("isa"));
}

}  // namespace dampbench::python
